#pragma once
// The compiled graph as report.json records it: passes run and culled, and every resource with its
// size, format, lifetime and the resources it shares memory with.
#include <nlohmann/json.hpp>

#include "graph/render_graph.h"

namespace aor {

nlohmann::json graphResourcesJson(const graph::RenderGraph& graph, const graph::CompiledGraph& compiled);

}  // namespace aor
