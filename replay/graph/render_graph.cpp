// Graph building and compilation: culling, lifetimes, memory aliasing, barrier derivation.
#include "graph/render_graph.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

namespace aor::graph {
namespace {

constexpr VkAccessFlags2 kWriteAccessBits =
    VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
    VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT |
    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_HOST_WRITE_BIT |
    VK_ACCESS_2_MEMORY_WRITE_BIT;

bool hasWrite(VkAccessFlags2 access) { return (access & kWriteAccessBits) != 0; }

bool isSubset(uint64_t part, uint64_t whole) { return (part & ~whole) == 0; }

VkImageUsageFlags usageOf(Access access) {
  switch (access) {
    case Access::SampledRead: return VK_IMAGE_USAGE_SAMPLED_BIT;
    case Access::StorageRead:
    case Access::StorageWrite: return VK_IMAGE_USAGE_STORAGE_BIT;
    case Access::TransferRead: return VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    case Access::TransferWrite:
    case Access::ClearWrite: return VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  }
  return 0;
}

std::string joinNames(const std::vector<std::string>& names) {
  std::string out;
  for (size_t i = 0; i < names.size(); ++i) {
    if (i) out += ", ";
    out += names[i];
  }
  return out;
}

void pushUnique(std::vector<ResourceId>& ids, ResourceId id) {
  if (std::find(ids.begin(), ids.end(), id) == ids.end()) ids.push_back(id);
}

// Per-resource synchronisation tracking while barriers are derived.
struct Tracker {
  ImageState state;                 // layout + every access not yet covered by a barrier (src scope)
  bool writeSeen = false;           // a write (or layout transition) exists that readers must see
  VkPipelineStageFlags2 visibleStages = 0;  // scopes the last write has been made visible to
  VkAccessFlags2 visibleAccess = 0;
};

}  // namespace

// ---------------------------------------------------------------------------------------------
// Building

void PassBuilder::read(ResourceId id, Access access) { declare(id, access, false); }

void PassBuilder::write(ResourceId id, Access access) { declare(id, access, true); }

void PassBuilder::declare(ResourceId id, Access access, bool asWrite) {
  PassDecl& pass = graph_.passes_.at(pass_);
  const char* verb = asWrite ? "writes" : "reads";
  if (id == kNoResource || id >= graph_.resources_.size()) {
    throw std::invalid_argument(fmt::format(
        "pass '{}' {} an invalid resource id ({})", pass.name, verb,
        id == kNoResource ? std::string("kNoResource") : std::to_string(id)));
  }
  if (isWrite(access) != asWrite) {
    throw std::invalid_argument(fmt::format("pass '{}' {} '{}' with a {} access ({})", pass.name, verb,
                                            graph_.resources_[id].name, asWrite ? "read" : "write",
                                            accessName(access)));
  }
  pass.accesses.emplace_back(id, access);
}

void PassBuilder::sideEffect() { graph_.passes_.at(pass_).sideEffect = true; }

namespace {
void validateDesc(const std::string& name, const ImageDesc& desc) {
  if (desc.width == 0 || desc.height == 0) {
    throw std::invalid_argument(
        fmt::format("image '{}' has an empty extent {}x{}", name, desc.width, desc.height));
  }
  if (bytesPerPixel(desc.format) == 0) {
    throw std::invalid_argument(fmt::format(
        "image '{}' uses VkFormat {}, which the render graph cannot size (add it to "
        "graph/formats.cpp)",
        name, static_cast<int>(desc.format)));
  }
}
}  // namespace

ResourceId RenderGraph::createImage(std::string name, ImageDesc desc) {
  validateDesc(name, desc);
  resources_.push_back(ResourceDecl{std::move(name), desc, ResourceKind::Transient, ImageState{}});
  return static_cast<ResourceId>(resources_.size() - 1);
}

ResourceId RenderGraph::importImage(std::string name, ImageDesc desc, ImageState initialState) {
  validateDesc(name, desc);
  resources_.push_back(ResourceDecl{std::move(name), desc, ResourceKind::Imported, initialState});
  return static_cast<ResourceId>(resources_.size() - 1);
}

HistoryPair RenderGraph::createHistory(std::string name, ImageDesc desc, bool previousValid,
                                       ImageState previousState, ImageState currentState) {
  validateDesc(name, desc);
  HistoryPair pair;
  if (previousValid) {
    resources_.push_back(ResourceDecl{name + ".previous", desc, ResourceKind::History, previousState, name, false});
    pair.previous = static_cast<ResourceId>(resources_.size() - 1);
  }
  resources_.push_back(ResourceDecl{name + ".current", desc, ResourceKind::History, currentState, name, true});
  pair.current = static_cast<ResourceId>(resources_.size() - 1);
  return pair;
}

uint32_t RenderGraph::addPass(std::string name, const std::function<void(PassBuilder&)>& setup,
                              std::function<void(PassContext&)> execute) {
  const auto index = static_cast<uint32_t>(passes_.size());
  passes_.push_back(PassDecl{std::move(name), {}, false, std::move(execute)});
  if (setup) {
    PassBuilder builder(*this, index);
    try {
      setup(builder);
    } catch (...) {
      passes_.pop_back();  // leave the graph as it was before the failed addPass
      throw;
    }
  }
  return index;
}

// ---------------------------------------------------------------------------------------------
// Compilation

CompiledGraph RenderGraph::compile() const {
  const size_t passCount = passes_.size();
  const size_t resourceCount = resources_.size();
  CompiledGraph out;
  out.resources.resize(resourceCount);

  // Producer of every read: the nearest earlier pass that writes the resource (or none).
  std::vector<std::vector<std::pair<ResourceId, int>>> readProducers(passCount);
  {
    std::vector<int> lastWriter(resourceCount, -1);
    for (size_t p = 0; p < passCount; ++p) {
      std::vector<ResourceId> reads;
      for (const auto& [id, access] : passes_[p].accesses) {
        if (!isWrite(access)) pushUnique(reads, id);
      }
      for (ResourceId id : reads) {
        const ResourceDecl& res = resources_[id];
        const bool mustBeWritten =
            res.kind == ResourceKind::Transient ||
            (res.kind == ResourceKind::History && res.historyCurrent);
        if (lastWriter[id] < 0 && mustBeWritten) {
          throw std::logic_error(fmt::format(
              "pass '{}' reads {} '{}' before any earlier pass writes it", passes_[p].name,
              res.kind == ResourceKind::Transient ? "transient" : "history image", res.name));
        }
        readProducers[p].emplace_back(id, lastWriter[id]);
      }
      for (const auto& [id, access] : passes_[p].accesses) {
        if (isWrite(access)) lastWriter[id] = static_cast<int>(p);
      }
    }
  }

  // 1. Culling: walk backwards from the roots (side-effect passes).
  std::vector<bool> live(passCount, false);
  for (size_t i = passCount; i-- > 0;) {
    if (passes_[i].sideEffect) live[i] = true;
    if (!live[i]) continue;
    for (const auto& [id, producer] : readProducers[i]) {
      if (producer >= 0) live[producer] = true;
    }
  }
  for (size_t p = 0; p < passCount; ++p) {
    if (live[p]) continue;
    std::vector<ResourceId> outputs;
    for (const auto& [id, access] : passes_[p].accesses) {
      if (isWrite(access)) pushUnique(outputs, id);
    }
    CulledPass culled{static_cast<uint32_t>(p), {}};
    if (outputs.empty()) {
      culled.reason = "no outputs and no side effects";
    } else {
      std::vector<std::string> names;
      std::vector<std::string> culledReaders;
      for (ResourceId id : outputs) {
        names.push_back(resources_[id].name);
        for (size_t q = p + 1; q < passCount; ++q) {
          for (const auto& [rid, producer] : readProducers[q]) {
            if (rid == id && producer == static_cast<int>(p)) {
              const std::string& reader = passes_[q].name;
              if (std::find(culledReaders.begin(), culledReaders.end(), reader) ==
                  culledReaders.end()) {
                culledReaders.push_back(reader);
              }
            }
          }
        }
      }
      culled.reason = fmt::format("writes {}, which no live pass reads", joinNames(names));
      if (!culledReaders.empty()) {
        culled.reason += fmt::format(" (read only by culled pass{} {})",
                                     culledReaders.size() > 1 ? "es" : "", joinNames(culledReaders));
      }
    }
    out.culled.push_back(std::move(culled));
  }

  // 2. Live passes in declaration order; lifetimes and usage.
  for (size_t p = 0; p < passCount; ++p) {
    if (!live[p]) continue;
    const int index = static_cast<int>(out.passes.size());
    out.passes.push_back(CompiledPass{static_cast<uint32_t>(p), {}});
    for (const auto& [id, access] : passes_[p].accesses) {
      CompiledResource& res = out.resources[id];
      if (!res.used) {
        res.used = true;
        res.firstPass = index;
      }
      res.lastPass = index;
      res.usage |= usageOf(access);
    }
  }

  // 3. Aliasing of transients with disjoint lifetimes; memory totals.
  std::vector<ResourceId> transients;
  for (ResourceId id = 0; id < resourceCount; ++id) {
    const CompiledResource& res = out.resources[id];
    if (!res.used) continue;
    const uint64_t bytes = imageBytes(resources_[id].desc);
    if (resources_[id].kind == ResourceKind::Transient) {
      transients.push_back(id);
      out.unaliasedTransientBytes += bytes;
    } else {
      out.persistentBytes += bytes;
    }
  }
  std::stable_sort(transients.begin(), transients.end(), [&](ResourceId a, ResourceId b) {
    return out.resources[a].firstPass < out.resources[b].firstPass;
  });
  for (ResourceId id : transients) {
    CompiledResource& res = out.resources[id];
    const uint64_t bytes = imageBytes(resources_[id].desc);
    int best = -1;
    for (size_t s = 0; s < out.slots.size(); ++s) {
      const MemorySlot& slot = out.slots[s];
      if (out.resources[slot.resources.back()].lastPass >= res.firstPass) continue;
      if (best < 0) {
        best = static_cast<int>(s);
        continue;
      }
      const uint64_t bestBytes = out.slots[best].bytes;
      const bool fits = slot.bytes >= bytes;
      const bool bestFits = bestBytes >= bytes;
      // Prefer a slot that already fits (the smallest such); otherwise the largest (least growth).
      if ((fits && !bestFits) || (fits && bestFits && slot.bytes < bestBytes) ||
          (!fits && !bestFits && slot.bytes > bestBytes)) {
        best = static_cast<int>(s);
      }
    }
    if (best < 0) {
      out.slots.emplace_back();
      best = static_cast<int>(out.slots.size() - 1);
    }
    MemorySlot& slot = out.slots[best];
    slot.resources.push_back(id);
    slot.bytes = std::max(slot.bytes, bytes);
    res.memorySlot = best;
  }
  for (const MemorySlot& slot : out.slots) out.transientBytes += slot.bytes;

  // 4. Barriers, derived from the declared accesses in execution order.
  std::vector<Tracker> trackers(resourceCount);
  for (ResourceId id = 0; id < resourceCount; ++id) {
    Tracker& t = trackers[id];
    if (resources_[id].kind == ResourceKind::Transient) continue;  // {NONE, NONE, UNDEFINED}
    t.state = resources_[id].initialState;
    // Contents written by earlier work are assumed visible unless that work's write is pending.
    t.writeSeen = hasWrite(t.state.access);
  }
  // Previous member of each transient's memory slot (its memory-reuse predecessor).
  std::vector<ResourceId> slotPredecessor(resourceCount, kNoResource);
  for (const MemorySlot& slot : out.slots) {
    for (size_t m = 1; m < slot.resources.size(); ++m) {
      slotPredecessor[slot.resources[m]] = slot.resources[m - 1];
    }
  }

  for (size_t index = 0; index < out.passes.size(); ++index) {
    CompiledPass& compiled = out.passes[index];
    const PassDecl& pass = passes_[compiled.pass];
    std::vector<ResourceId> touched;
    for (const auto& [id, access] : pass.accesses) pushUnique(touched, id);

    for (ResourceId id : touched) {
      const ImageState need = requiredState(pass, id);
      const bool writes = hasWrite(need.access);
      Tracker& t = trackers[id];
      const bool firstUse = out.resources[id].firstPass == static_cast<int>(index);

      if (firstUse && resources_[id].kind == ResourceKind::Transient) {
        // Contents are discarded; the memory may still be in use by the previous slot member.
        ImageState before{};
        if (slotPredecessor[id] != kNoResource) {
          const ImageState& prev = trackers[slotPredecessor[id]].state;
          before.stage = prev.stage;
          before.access = prev.access;
        }
        before.layout = VK_IMAGE_LAYOUT_UNDEFINED;
        compiled.barriersBefore.push_back(Barrier{id, before, need});
        t.state = need;
        t.writeSeen = writes;
        t.visibleStages = 0;
        t.visibleAccess = 0;
        continue;
      }

      const bool layoutChange = t.state.layout != need.layout;
      const bool pendingWrite = hasWrite(t.state.access);
      const bool anyPrevious = t.state.stage != 0 || t.state.access != 0;
      bool barrier = layoutChange || pendingWrite;
      if (writes) {
        barrier = barrier || anyPrevious;  // WAR (and WAW)
      } else if (t.writeSeen) {
        // Reads of already-visible data need nothing; a reader outside the visible scopes does.
        barrier = barrier || !isSubset(need.stage, t.visibleStages) ||
                  !isSubset(need.access, t.visibleAccess);
      }

      if (barrier) {
        compiled.barriersBefore.push_back(Barrier{id, t.state, need});
        if (layoutChange || pendingWrite) {
          // The transition (or the pending write) is visible exactly to this barrier's dst scope.
          t.writeSeen = t.writeSeen || layoutChange;
          t.visibleStages = need.stage;
          t.visibleAccess = need.access;
        } else {
          t.visibleStages |= need.stage;
          t.visibleAccess |= need.access;
        }
        t.state = need;
      } else {
        // Read after read in the same layout: accumulate the readers for the next barrier's src.
        t.state.stage |= need.stage;
        t.state.access |= need.access;
      }
      if (writes) {
        t.state = need;
        t.writeSeen = true;
        t.visibleStages = 0;
        t.visibleAccess = 0;
      }
    }
  }

  for (ResourceId id = 0; id < resourceCount; ++id) {
    CompiledResource& res = out.resources[id];
    res.finalState = res.used ? trackers[id].state
                              : (resources_[id].kind == ResourceKind::Transient
                                     ? ImageState{}
                                     : resources_[id].initialState);
  }
  return out;
}

}  // namespace aor::graph
