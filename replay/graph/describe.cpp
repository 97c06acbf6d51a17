// Text and Graphviz explanations of a compiled graph.
#include <string>
#include <vector>

#include <fmt/format.h>

#include "graph/render_graph.h"

namespace aor::graph {
namespace {

constexpr double kMiB = 1024.0 * 1024.0;

std::string bytesText(uint64_t bytes) {
  return fmt::format("{} bytes ({:.2f} MiB)", bytes, static_cast<double>(bytes) / kMiB);
}

std::string formatText(VkFormat format) {
  const char* name = formatName(format);
  if (bytesPerPixel(format) == 0 && format != VK_FORMAT_UNDEFINED) {
    return fmt::format("VkFormat({})", static_cast<int>(format));
  }
  return name;
}

// "1920x1080 R16_SFLOAT", with ", 5 mips" / ", 4 layers" where there are more than one; "buffer".
std::string shapeText(const ResourceDecl& decl) {
  if (decl.isBuffer()) return "buffer";
  std::string text = fmt::format("{}x{} {}", decl.desc.width, decl.desc.height, formatText(decl.desc.format));
  if (decl.desc.mipLevels > 1) text += fmt::format(", {} mips", decl.desc.mipLevels);
  if (decl.desc.arrayLayers > 1) text += fmt::format(", {} layers", decl.desc.arrayLayers);
  return text;
}

// Graphviz double-quoted string with escapes; `\n` in the input becomes a centred line break.
std::string dotQuote(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': break;
      default: out += c;
    }
  }
  out += '"';
  return out;
}

}  // namespace

std::string passName(const RenderGraph& graph, const CompiledGraph& compiled, int index) {
  if (index < 0 || static_cast<size_t>(index) >= compiled.passes.size()) return "-";
  return graph.passes()[compiled.passes[index].pass].name;
}

std::vector<ResourceId> aliasesOf(const CompiledGraph& compiled, ResourceId id) {
  std::vector<ResourceId> out;
  const int slot = compiled.resources[id].memorySlot;
  if (slot < 0 || static_cast<size_t>(slot) >= compiled.slots.size()) return out;
  for (ResourceId other : compiled.slots[slot].resources) {
    if (other != id) out.push_back(other);
  }
  return out;
}

std::string describe(const RenderGraph& graph, const CompiledGraph& compiled) {
  const auto& passes = graph.passes();
  const auto& resources = graph.resources();
  std::string out;

  out += fmt::format("passes run: {}\n", compiled.passes.size());
  for (size_t i = 0; i < compiled.passes.size(); ++i) {
    const CompiledPass& cp = compiled.passes[i];
    const PassDecl& pass = passes[cp.pass];
    out += fmt::format("  [{}] {}{}\n", i, pass.name, pass.sideEffect ? " (side effect)" : "");
    std::string reads, writes;
    for (size_t a = 0; a < pass.accesses.size(); ++a) {
      const AccessDecl& access = pass.accesses[a];
      if (!cp.accessLive[a]) continue;  // a writeIfRead nobody reads: not done
      std::string& list = isWrite(access.access) ? writes : reads;
      if (!list.empty()) list += ", ";
      const ResourceDecl& res = resources[access.resource];
      list += fmt::format("{}{} ({})", res.name, rangeText(res, access.range), accessName(access.access));
    }
    if (!reads.empty()) out += fmt::format("      reads:  {}\n", reads);
    if (!writes.empty()) out += fmt::format("      writes: {}\n", writes);
    for (const Barrier& b : cp.barriersBefore) {
      const ResourceDecl& res = resources[b.resource];
      std::string layouts = res.isBuffer() ? "buffer" : fmt::format("{} -> {}", layoutName(b.before.layout),
                                                                   layoutName(b.after.layout));
      out += fmt::format("      barrier {}{}: {}, {} -> {} ({} -> {})\n", res.name, rangeText(res, b.range), layouts,
                         stageNames(b.before.stage), stageNames(b.after.stage), accessNames(b.before.access),
                         accessNames(b.after.access));
    }
  }

  out += fmt::format("passes culled: {}\n", compiled.culled.size());
  for (const CulledPass& c : compiled.culled) {
    out += fmt::format("  {}: {}\n", passes[c.pass].name, c.reason);
  }

  out += fmt::format("resources: {}\n", resources.size());
  for (ResourceId id = 0; id < resources.size(); ++id) {
    const ResourceDecl& decl = resources[id];
    const CompiledResource& res = compiled.resources[id];
    out += fmt::format("  {} [{}] {}, {}", decl.name, kindName(decl.kind), shapeText(decl), bytesText(decl.bytes()));
    if (!res.used) {
      out += ": not allocated (unused)\n";
      continue;
    }
    out += fmt::format(": lifetime {} .. {}", passName(graph, compiled, res.firstPass),
                       passName(graph, compiled, res.lastPass));
    if (res.memorySlot >= 0) {
      out += fmt::format(", memory slot {}", res.memorySlot);
      const auto aliases = aliasesOf(compiled, id);
      if (aliases.empty()) {
        out += " (alone)";
      } else {
        out += " (aliases ";
        for (size_t a = 0; a < aliases.size(); ++a) {
          out += (a ? ", " : "") + resources[aliases[a]].name;
        }
        out += ")";
      }
    } else {
      out += ", persistent";
    }
    out += "\n";
  }

  out += "totals:\n";
  out += fmt::format("  transient (aliased): {} in {} slot{}\n", bytesText(compiled.transientBytes),
                     compiled.slots.size(), compiled.slots.size() == 1 ? "" : "s");
  out += fmt::format("  transient unaliased: {}\n", bytesText(compiled.unaliasedTransientBytes));
  out += fmt::format("  persistent:          {}\n", bytesText(compiled.persistentBytes));
  out += fmt::format("  peak:                {}\n", bytesText(compiled.peakBytes()));
  return out;
}

std::string toDot(const RenderGraph& graph, const CompiledGraph& compiled) {
  const auto& passes = graph.passes();
  const auto& resources = graph.resources();
  std::vector<const CulledPass*> culledBy(passes.size(), nullptr);
  for (const CulledPass& c : compiled.culled) {
    if (c.pass < passes.size()) culledBy[c.pass] = &c;
  }
  std::vector<int> order(passes.size(), -1);
  for (size_t i = 0; i < compiled.passes.size(); ++i) order[compiled.passes[i].pass] = int(i);

  std::string out = "digraph render_graph {\n  rankdir=LR;\n  node [fontname=\"Helvetica\"];\n"
                    "  edge [fontname=\"Helvetica\", fontsize=10];\n";
  for (size_t p = 0; p < passes.size(); ++p) {
    const PassDecl& pass = passes[p];
    if (const CulledPass* c = culledBy[p]) {
      out += fmt::format(
          "  p{} [shape=box, style=dashed, color=grey, fontcolor=grey, label={}, tooltip={}];\n", p,
          dotQuote(pass.name + "\nculled: " + c->reason), dotQuote(c->reason));
    } else {
      std::string label = order[p] >= 0 ? fmt::format("[{}] {}", order[p], pass.name) : pass.name;
      if (pass.sideEffect) label += "\n(side effect)";
      out += fmt::format("  p{} [shape=box, style={}, label={}];\n", p,
                         pass.sideEffect ? "bold" : "solid", dotQuote(label));
    }
  }
  for (ResourceId id = 0; id < resources.size(); ++id) {
    const ResourceDecl& decl = resources[id];
    const CompiledResource& res = compiled.resources[id];
    std::string label = fmt::format("{}\n{}", decl.name, shapeText(decl));
    std::string style;
    if (!res.used) {
      label += "\nunused";
      style = "style=dashed, color=grey, fontcolor=grey";
    } else if (decl.kind == ResourceKind::History) {
      style = "style=filled, fillcolor=lightgoldenrod1";
    } else if (decl.kind == ResourceKind::Imported) {
      style = "style=filled, fillcolor=lightblue, peripheries=2";
    } else {
      label += fmt::format("\nslot {}", res.memorySlot);
      style = "style=filled, fillcolor=palegreen";
    }
    out += fmt::format("  r{} [shape=ellipse, {}, label={}];\n", id, style, dotQuote(label));
  }
  for (size_t p = 0; p < passes.size(); ++p) {
    const char* extra = culledBy[p] ? ", style=dashed, color=grey, fontcolor=grey" : "";
    for (const AccessDecl& a : passes[p].accesses) {
      if (a.resource >= resources.size()) continue;
      std::string label = dotQuote(accessName(a.access) + rangeText(resources[a.resource], a.range));
      if (isWrite(a.access)) {
        out += fmt::format("  p{} -> r{} [label={}{}];\n", p, a.resource, label, extra);
      } else {
        out += fmt::format("  r{} -> p{} [label={}{}];\n", a.resource, p, label, extra);
      }
    }
  }
  out += "}\n";
  return out;
}

}  // namespace aor::graph
