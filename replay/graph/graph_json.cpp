#include "graph/graph_json.h"

namespace aor {

nlohmann::json graphResourcesJson(const graph::RenderGraph& graph, const graph::CompiledGraph& compiled) {
  nlohmann::json resources = nlohmann::json::array();
  for (graph::ResourceId id = 0; id < graph.resources().size(); ++id) {
    const auto& decl = graph.resources()[id];
    const auto& res = compiled.resources[id];
    nlohmann::json r{{"name", decl.name}, {"kind", graph::kindName(decl.kind)}, {"bytes", decl.bytes()},
                     {"allocated", res.used}};
    if (decl.isBuffer()) {
      r["type"] = "buffer";
    } else {
      r["type"] = "image";
      r["width"] = decl.desc.width;
      r["height"] = decl.desc.height;
      r["format"] = graph::formatName(decl.desc.format);
      if (decl.desc.mipLevels > 1) r["mip_levels"] = decl.desc.mipLevels;
      if (decl.desc.arrayLayers > 1) r["array_layers"] = decl.desc.arrayLayers;
    }
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
