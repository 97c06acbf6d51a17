// Compile stages 3 and 4: execution order and lifetimes, then memory slots shared by transients
// whose lifetimes do not overlap (aliasing).
#include <algorithm>

#include "graph/compile_stages.h"

namespace aor::graph::stages {
namespace {

VkImageUsageFlags imageUsageOf(Access access) {
  switch (access) {
    case Access::SampledRead: return VK_IMAGE_USAGE_SAMPLED_BIT;
    case Access::StorageRead:
    case Access::StorageWrite: return VK_IMAGE_USAGE_STORAGE_BIT;
    case Access::TransferRead: return VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    case Access::TransferWrite:
    case Access::ClearWrite: return VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    case Access::UniformRead:
    case Access::IndirectRead:
    case Access::AccelerationStructureRead: return 0;
  }
  return 0;
}

VkBufferUsageFlags bufferUsageOf(Access access) {
  switch (access) {
    case Access::StorageRead:
    case Access::StorageWrite: return VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    case Access::UniformRead: return VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT;
    case Access::IndirectRead: return VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
    case Access::AccelerationStructureRead: return VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR;
    case Access::TransferRead: return VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
    case Access::TransferWrite:
    case Access::ClearWrite: return VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    case Access::SampledRead: return 0;
  }
  return 0;
}

// The best slot for a transient of `bytes` first used at `firstPass`, or -1 for a new one: a slot of
// the same resource type whose last member is dead by then; the smallest that already fits,
// otherwise the largest (least growth).
int chooseSlot(const std::vector<ResourceDecl>& resources, const CompiledGraph& out, ResourceType type, uint64_t bytes,
               int firstPass) {
  int best = -1;
  for (size_t s = 0; s < out.slots.size(); ++s) {
    const MemorySlot& slot = out.slots[s];
    if (resources[slot.resources.front()].type != type) continue;
    if (out.resources[slot.resources.back()].lastPass >= firstPass) continue;
    if (best < 0) {
      best = int(s);
      continue;
    }
    const uint64_t bestBytes = out.slots[size_t(best)].bytes;
    const bool fits = slot.bytes >= bytes, bestFits = bestBytes >= bytes;
    if ((fits && !bestFits) || (fits && bestFits && slot.bytes < bestBytes) || (!fits && !bestFits && slot.bytes > bestBytes))
      best = int(s);
  }
  return best;
}

}  // namespace

void lifetimes(const std::vector<ResourceDecl>& resources, const std::vector<PassDecl>& passes, const Liveness& liveness, CompiledGraph& out) {
  for (size_t p = 0; p < passes.size(); ++p) {
    if (!liveness.live[p]) continue;
    const int index = int(out.passes.size());
    out.passes.push_back(CompiledPass{uint32_t(p), {}, liveness.accessLive[p]});
    for (size_t a = 0; a < passes[p].accesses.size(); ++a) {
      if (!liveness.accessLive[p][a]) continue;
      const AccessDecl& access = passes[p].accesses[a];
      CompiledResource& res = out.resources[access.resource];
      if (!res.used) {
        res.used = true;
        res.firstPass = index;
      }
      res.lastPass = index;
      if (resources[access.resource].isBuffer())
        res.bufferUsage |= bufferUsageOf(access.access);
      else
        res.usage |= imageUsageOf(access.access);
    }
  }
}

void alias(const std::vector<ResourceDecl>& resources, CompiledGraph& out) {
  std::vector<ResourceId> transients;
  for (ResourceId id = 0; id < resources.size(); ++id) {
    if (!out.resources[id].used) continue;
    if (resources[id].kind == ResourceKind::Transient) {
      transients.push_back(id);
      out.unaliasedTransientBytes += resources[id].bytes();
    } else {
      out.persistentBytes += resources[id].bytes();
    }
  }
  std::stable_sort(transients.begin(), transients.end(),
                   [&](ResourceId a, ResourceId b) { return out.resources[a].firstPass < out.resources[b].firstPass; });
  for (ResourceId id : transients) {
    CompiledResource& res = out.resources[id];
    const uint64_t bytes = resources[id].bytes();
    int slot = chooseSlot(resources, out, resources[id].type, bytes, res.firstPass);
    if (slot < 0) {
      out.slots.emplace_back();
      slot = int(out.slots.size() - 1);
    }
    out.slots[size_t(slot)].resources.push_back(id);
    out.slots[size_t(slot)].bytes = std::max(out.slots[size_t(slot)].bytes, bytes);
    res.memorySlot = slot;
  }
  for (const MemorySlot& slot : out.slots) out.transientBytes += slot.bytes;
}

}  // namespace aor::graph::stages
