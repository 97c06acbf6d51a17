#pragma once
// The render graph drawn for report.html: the DOT text of graph::toDot laid out by Graphviz's
// library (Debian libgraphviz-dev), as inline SVG.
#include <cstddef>
#include <string>

namespace aor::html {

// Graphviz's dot layout grows explosively with long pass chains (40 chained passes took 1.6 s,
// 60 took 112 s, 100 did not finish in 120 s), so larger graphs are not laid out.
inline constexpr size_t kMaxDrawnPasses = 32;

// The <svg> element of the laid-out graph; empty when Graphviz cannot lay it out or the graph has
// more than kMaxDrawnPasses passes (the page then shows the DOT text instead).
std::string graphSvg(const std::string& dot);
size_t passNodes(const std::string& dot);  // the pass nodes (p0, p1, ...) of graph::toDot's text

// The simpler drawing for graphs of any size, in time linear in the graph: the passes one per row
// in execution order (culled ones grey), and each resource as arcs on the right from the pass
// that writes it to each pass that reads it (its name as the arc's tooltip).
std::string passListSvg(const std::string& dot);

}  // namespace aor::html
