#include "report/graph_json.h"

namespace aor {

nlohmann::json graphResourcesJson(const graph::RenderGraph& graph, const graph::CompiledGraph& compiled) {
  nlohmann::json resources = nlohmann::json::array();
  for (graph::ResourceId id = 0; id < graph.resources().size(); ++id) {
    const auto& decl = graph.resources()[id];
    const auto& res = compiled.resources[id];
    nlohmann::json r{{"name", decl.name}, {"kind", graph::kindName(decl.kind)}, {"width", decl.desc.width},
                     {"height", decl.desc.height}, {"format", graph::formatName(decl.desc.format)},
                     {"bytes", graph::imageBytes(decl.desc)}, {"allocated", res.used}};
    if (res.used) {
      r["first_pass"] = graph::passName(graph, compiled, res.firstPass);
      r["last_pass"] = graph::passName(graph, compiled, res.lastPass);
    }
    nlohmann::json aliases = nlohmann::json::array();
    if (res.memorySlot >= 0) r["memory_slot"] = res.memorySlot;
    for (auto other : graph::aliasesOf(compiled, id)) aliases.push_back(graph.resources()[other].name);
    r["aliases"] = aliases;
    resources.push_back(r);
  }
  return resources;
}

}  // namespace aor
