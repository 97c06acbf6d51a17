#include "report/html/graph_svg.h"

#include <graphviz/gvc.h>

#include <cctype>
#include <mutex>

namespace aor::html {

// Node lines "  pN [...]" (edge lines "  pN -> rM;" are not counted).
size_t passNodes(const std::string& dot) {
  size_t count = 0;
  for (size_t at = dot.find("\n  p"); at != std::string::npos; at = dot.find("\n  p", at + 1)) {
    size_t end = at + 4;
    while (end < dot.size() && std::isdigit(static_cast<unsigned char>(dot[end]))) ++end;
    count += end > at + 4 && dot.compare(end, 2, " [") == 0;
  }
  return count;
}

std::string graphSvg(const std::string& dot) {
  if (dot.empty() || passNodes(dot) > kMaxDrawnPasses) return {};
  static std::mutex graphviz;  // its context and error state are global
  std::lock_guard lock(graphviz);
  GVC_t* context = gvContext();
  if (!context) return {};
  std::string svg;
  if (Agraph_t* graph = agmemread(dot.c_str())) {
    if (gvLayout(context, graph, "dot") == 0) {
      char* data = nullptr;
      unsigned int length = 0;
      if (gvRenderData(context, graph, "svg", &data, &length) == 0 && data) svg.assign(data, length);
      gvFreeRenderData(data);
      gvFreeLayout(context, graph);
    }
    agclose(graph);
  }
  gvFreeContext(context);
  // Inline in HTML: the element alone, without the XML prolog and DOCTYPE.
  auto start = svg.find("<svg");
  return start == std::string::npos ? std::string() : svg.substr(start);
}

}  // namespace aor::html
