// Compile stage 5: barriers and layout transitions, per mip level and array layer (one state for a
// buffer), derived from the live accesses in execution order; then merged into ranges.
#include <algorithm>
#include <optional>

#include "graph/compile_stages.h"

namespace aor::graph::stages {
namespace {

constexpr VkAccessFlags2 kWriteAccessBits =
    VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT |
    VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
    VK_ACCESS_2_HOST_WRITE_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;

bool hasWrite(VkAccessFlags2 access) { return (access & kWriteAccessBits) != 0; }
bool isSubset(uint64_t part, uint64_t whole) { return (part & ~whole) == 0; }
bool sameState(const ResourceState& a, const ResourceState& b) {
  return a.stage == b.stage && a.access == b.access && a.layout == b.layout;
}

// A buffer has no layout; and vkCmdFillBuffer (ClearWrite) runs in the CLEAR stage by the current
// specification but in COPY by earlier ones and their validation layers (Debian 12's), so a buffer
// clear is synchronised as both.
ResourceState bufferState(ResourceState s) {
  if (s.stage & VK_PIPELINE_STAGE_2_CLEAR_BIT) s.stage |= VK_PIPELINE_STAGE_2_COPY_BIT;
  s.layout = VK_IMAGE_LAYOUT_UNDEFINED;
  return s;
}

// Synchronisation of one subresource while barriers are derived.
struct Tracker {
  ResourceState state;                         // layout + every access not yet covered by a barrier (src scope)
  bool writeSeen = false;                   // a write (or layout transition) exists that readers must see
  VkPipelineStageFlags2 visibleStages = 0;  // scopes the last write has been made visible to
  VkAccessFlags2 visibleAccess = 0;
};

struct SubBarrier {
  uint32_t mip, layer;
  ResourceState before, after;
};

// The barrier one subresource needs before an access needing `need`, if any; updates the tracker.
std::optional<SubBarrier> track(Tracker& t, const ResourceState& need, uint32_t mip, uint32_t layer) {
  const bool writes = hasWrite(need.access);
  const bool layoutChange = t.state.layout != need.layout;
  const bool pendingWrite = hasWrite(t.state.access);
  const bool anyPrevious = t.state.stage != 0 || t.state.access != 0;
  bool barrier = layoutChange || pendingWrite;
  if (writes) {
    barrier = barrier || anyPrevious;  // WAR (and WAW)
  } else if (t.writeSeen) {
    // Reads of already-visible data need nothing; a reader outside the visible scopes does.
    barrier = barrier || !isSubset(need.stage, t.visibleStages) || !isSubset(need.access, t.visibleAccess);
  }
  std::optional<SubBarrier> out;
  if (barrier) {
    out = SubBarrier{mip, layer, t.state, need};
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
  return out;
}

// Subresource barriers with equal states merged: runs of mips within a layer, then runs of layers
// whose mip runs are the same.
std::vector<Barrier> mergeRanges(ResourceId id, std::vector<SubBarrier> subs) {
  std::vector<Barrier> perLayer;
  for (const SubBarrier& s : subs) {
    Barrier* last = perLayer.empty() ? nullptr : &perLayer.back();
    if (last && last->range.baseLayer == s.layer && last->range.baseMip + last->range.mipCount == s.mip &&
        sameState(last->before, s.before) && sameState(last->after, s.after)) {
      ++last->range.mipCount;
      continue;
    }
    perLayer.push_back(Barrier{id, s.before, s.after, Subresources{s.mip, 1, s.layer, 1}});
  }
  std::vector<Barrier> merged;
  for (const Barrier& b : perLayer) {
    auto same = std::find_if(merged.begin(), merged.end(), [&](const Barrier& m) {
      return m.range.baseLayer + m.range.layerCount == b.range.baseLayer && m.range.baseMip == b.range.baseMip &&
             m.range.mipCount == b.range.mipCount && sameState(m.before, b.before) && sameState(m.after, b.after);
    });
    if (same != merged.end()) ++same->range.layerCount;
    else merged.push_back(b);
  }
  return merged;
}

// What the previous member of a transient's memory slot left pending: every stage and access of
// every one of its subresources.
ResourceState slotPredecessorState(const std::vector<Tracker>& trackers) {
  ResourceState s;
  for (const Tracker& t : trackers) {
    s.stage |= t.state.stage;
    s.access |= t.state.access;
  }
  return s;
}

}  // namespace

void barriers(const std::vector<ResourceDecl>& resources, const std::vector<PassDecl>& passes, CompiledGraph& out) {
  std::vector<std::vector<Tracker>> trackers(resources.size());
  for (ResourceId id = 0; id < resources.size(); ++id) {
    const ResourceDecl& res = resources[id];
    trackers[id].resize(res.subresourceCount());
    if (res.kind == ResourceKind::Transient) continue;  // {NONE, NONE, UNDEFINED}
    for (uint32_t s = 0; s < trackers[id].size(); ++s) {
      // Contents written by earlier work are assumed visible unless that work's write is pending.
      trackers[id][s].state = res.initialStateOf(s);
      trackers[id][s].writeSeen = hasWrite(trackers[id][s].state.access);
    }
  }
  std::vector<ResourceId> slotPredecessor(resources.size(), kNoResource);
  for (const MemorySlot& slot : out.slots)
    for (size_t m = 1; m < slot.resources.size(); ++m) slotPredecessor[slot.resources[m]] = slot.resources[m - 1];

  for (size_t index = 0; index < out.passes.size(); ++index) {
    CompiledPass& compiled = out.passes[index];
    const PassDecl& pass = passes[compiled.pass];
    std::vector<ResourceId> touched;
    for (size_t a = 0; a < pass.accesses.size(); ++a)
      if (compiled.accessLive[a] && !std::count(touched.begin(), touched.end(), pass.accesses[a].resource))
        touched.push_back(pass.accesses[a].resource);

    for (ResourceId id : touched) {
      const ResourceDecl& res = resources[id];
      const bool firstUse = out.resources[id].firstPass == int(index) && res.kind == ResourceKind::Transient;
      const ResourceId predecessor = slotPredecessor[id];
      const uint32_t mips = res.isBuffer() ? 1 : res.desc.mipLevels, layers = res.isBuffer() ? 1 : res.desc.arrayLayers;
      std::vector<SubBarrier> subs;
      for (uint32_t layer = 0; layer < layers; ++layer)
        for (uint32_t mip = 0; mip < mips; ++mip) {
          Tracker& t = trackers[id][layer * mips + mip];
          ResourceState need = requiredState(pass, id, Subresources{mip, 1, layer, 1});
          if (res.isBuffer()) need = bufferState(need);
          const bool touchedHere = need.stage != 0;
          if (firstUse && predecessor != kNoResource) {
            // The memory may still be in use by the slot's previous member: every subresource waits
            // for it, and one this pass does not touch is moved to GENERAL now, so its first later
            // access chains after this wait.
            ResourceState before = slotPredecessorState(trackers[predecessor]);
            before.layout = VK_IMAGE_LAYOUT_UNDEFINED;
            ResourceState after = touchedHere ? need : ResourceState{need.stage | requiredState(pass, id).stage, 0,
                                                               res.isBuffer() ? VK_IMAGE_LAYOUT_UNDEFINED : VK_IMAGE_LAYOUT_GENERAL};
            subs.push_back({mip, layer, before, after});
            t = Tracker{after, touchedHere ? hasWrite(need.access) : true, 0, 0};
            continue;
          }
          if (!touchedHere) continue;
          if (firstUse && res.isBuffer()) {  // fresh memory, nothing to wait for, no layout
            t = Tracker{need, hasWrite(need.access), 0, 0};
            continue;
          }
          if (firstUse) {  // contents are discarded
            subs.push_back({mip, layer, ResourceState{0, 0, VK_IMAGE_LAYOUT_UNDEFINED}, need});
            t = Tracker{need, hasWrite(need.access), 0, 0};
            continue;
          }
          if (auto b = track(t, need, mip, layer)) subs.push_back(*b);
        }
      for (Barrier& b : mergeRanges(id, std::move(subs))) compiled.barriersBefore.push_back(b);
    }
  }

  for (ResourceId id = 0; id < resources.size(); ++id) {
    CompiledResource& res = out.resources[id];
    const ResourceDecl& decl = resources[id];
    res.finalStates.clear();
    for (uint32_t s = 0; s < decl.subresourceCount(); ++s)
      res.finalStates.push_back(res.used ? trackers[id][s].state
                                         : (decl.kind == ResourceKind::Transient ? ResourceState{} : decl.initialStateOf(s)));
    res.finalState = res.finalStates.front();
  }
}

}  // namespace aor::graph::stages
