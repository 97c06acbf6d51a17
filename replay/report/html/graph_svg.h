#pragma once
// The render graph drawn for report.html: the DOT text of graph::toDot laid out by Graphviz's
// library (Debian libgraphviz-dev), as inline SVG.
#include <string>

namespace aor::html {

// The <svg> element of the laid-out graph; empty when Graphviz cannot lay it out (the page then
// shows the DOT text instead).
std::string graphSvg(const std::string& dot);

}  // namespace aor::html
