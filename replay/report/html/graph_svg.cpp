#include "report/html/graph_svg.h"

#include <graphviz/gvc.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <mutex>
#include <sstream>
#include <vector>

#include <fmt/format.h>

#include "report/svg_plot.h"

namespace aor::html {

namespace {

struct ListedPass {
  std::string label;  // the first line of its DOT label
  bool culled = false;
};
struct Arc {
  size_t from, to;  // rows
  std::string resource;
  bool culled = false;
};

// The value of `label="..."` in a DOT attribute list, up to its first "\n", unescaped.
std::string labelOf(const std::string& line) {
  size_t at = line.find("label=\"");
  if (at == std::string::npos) return {};
  std::string out;
  for (at += 7; at < line.size() && line[at] != '"'; ++at) {
    if (line[at] == '\\' && at + 1 < line.size()) {
      if (line[++at] == 'n') break;
    }
    out += line[at];
  }
  return out;
}

// Where the digits from `at` end (`at` when there are none).
size_t digitsEnd(const std::string& text, size_t at) {
  while (at < text.size() && std::isdigit(static_cast<unsigned char>(text[at]))) ++at;
  return at;
}

// The number after the prefix letter of a node id ("p12" -> 12), or npos.
size_t idNumber(const std::string& text, size_t at) {
  const size_t end = digitsEnd(text, at);
  return end == at ? std::string::npos : size_t(std::stoul(text.substr(at, end - at)));
}

}  // namespace

// Node lines "  pN [...]" (edge lines "  pN -> rM;" are not counted).
size_t passNodes(const std::string& dot) {
  size_t count = 0;
  for (size_t at = dot.find("\n  p"); at != std::string::npos; at = dot.find("\n  p", at + 1)) {
    const size_t end = digitsEnd(dot, at + 4);
    count += end > at + 4 && dot.compare(end, 2, " [") == 0;
  }
  return count;
}

std::string passListSvg(const std::string& dot) {
  std::map<size_t, size_t> rowOf;  // pass id -> row
  std::vector<ListedPass> passes;
  std::map<size_t, std::string> resources;
  std::map<size_t, std::vector<size_t>> writers, readers;  // resource id -> pass ids
  std::istringstream in(dot);
  for (std::string line; std::getline(in, line);) {
    if (line.size() < 4 || line[0] != ' ' || line[1] != ' ') continue;
    const char kind = line[2];
    const size_t id = idNumber(line, 3);
    if (id == std::string::npos || (kind != 'p' && kind != 'r')) continue;
    const size_t arrow = line.find(" -> ");
    if (arrow == std::string::npos) {
      if (kind == 'p') {
        rowOf[id] = passes.size();
        passes.push_back({labelOf(line), line.find("style=dashed") != std::string::npos});
      } else {
        resources[id] = labelOf(line);
      }
      continue;
    }
    const size_t other = idNumber(line, arrow + 5);
    if (other == std::string::npos) continue;
    if (kind == 'p') writers[other].push_back(id);  // "pN -> rM": pass N writes resource M
    else readers[id].push_back(other);               // "rM -> pN": pass N reads it
  }
  std::vector<Arc> arcs;
  for (const auto& [resource, from] : writers)
    for (size_t w : from)
      for (size_t r : readers[resource])
        if (rowOf.count(w) && rowOf.count(r))
          arcs.push_back({rowOf[w], rowOf[r], resources[resource], passes[rowOf[w]].culled || passes[rowOf[r]].culled});
  constexpr double kRow = 22, kBoxWidth = 300, kTop = 10;
  const double width = kBoxWidth + 40 + 12 * std::min<double>(double(passes.size()), 40);
  std::string svg = fmt::format("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{:.0f}\" height=\"{:.0f}\" font-family=\"Helvetica\" "
                                "font-size=\"12\">\n",
                                width, kTop * 2 + kRow * double(passes.size()));
  for (size_t i = 0; i < passes.size(); ++i) {
    const char* colour = passes[i].culled ? "grey" : "#222";
    svg += fmt::format("<rect x=\"10\" y=\"{:.0f}\" width=\"{:.0f}\" height=\"{:.0f}\" fill=\"none\" stroke=\"{}\"{}/>"
                       "<text x=\"16\" y=\"{:.0f}\" fill=\"{}\">{}</text>\n",
                       kTop + kRow * double(i), kBoxWidth, kRow - 4, colour, passes[i].culled ? " stroke-dasharray=\"4 3\"" : "",
                       kTop + kRow * double(i) + 13, colour, escapeXml(passes[i].label));
  }
  for (const Arc& a : arcs) {
    const double y0 = kTop + kRow * double(a.from) + 9, y1 = kTop + kRow * double(a.to) + 9;
    const double reach = 10 + 12 * std::min<double>(std::abs(double(a.to) - double(a.from)), 40);
    svg += fmt::format("<path d=\"M {0:.0f} {1:.0f} C {2:.0f} {1:.0f}, {2:.0f} {3:.0f}, {0:.0f} {3:.0f}\" fill=\"none\" stroke=\"{4}\"{5}>"
                       "<title>{6}</title></path>\n",
                       10 + kBoxWidth, y0, 10 + kBoxWidth + reach, y1, a.culled ? "grey" : "#3b6ea5",
                       a.culled ? " stroke-dasharray=\"4 3\"" : "", escapeXml(a.resource));
  }
  return svg + "</svg>";
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
