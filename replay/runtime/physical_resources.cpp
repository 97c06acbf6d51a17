#include "runtime/physical_resources.h"

#include <fmt/format.h>

#include "vk/context.h"

namespace aor {
namespace {

constexpr VkImageUsageFlags kPersistentUsage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_STORAGE_BIT |
                                               VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
constexpr VkBufferUsageFlags kPersistentBufferUsage =
    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT |
    VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;

ImageShape shapeOf(const graph::ImageDesc& d) { return {d.width, d.height, d.format, d.mipLevels, d.arrayLayers}; }

bool sameShape(const GpuImage& image, const graph::ImageDesc& d) {
  return image.width == d.width && image.height == d.height && image.format == d.format && image.mipLevels == d.mipLevels &&
         image.arrayLayers == d.arrayLayers;
}

}  // namespace

PhysicalResources::~PhysicalResources() {
  releaseTransients();
  for (auto& [name, p] : persistent_) destroy(p);
}

void PhysicalResources::destroy(Persistent& p) {
  destroyImage(vk_, p.image);
  destroyBuffer(vk_, p.buffer);
}

std::string PhysicalResources::historyKey(const std::string& base, bool current) const {
  auto parity = historyParity_.count(base) ? historyParity_.at(base) : 0;
  return fmt::format("{}#{}", base, current ? parity : 1 - parity);
}

std::string PhysicalResources::physicalKey(const graph::ResourceDecl& decl) const {
  return decl.kind == graph::ResourceKind::History ? historyKey(decl.historyBase, decl.historyCurrent) : decl.name;
}

graph::ResourceState PhysicalResources::historyState(const std::string& base, bool current) const {
  auto it = persistent_.find(historyKey(base, current));
  return it == persistent_.end() || it->second.states.empty() ? graph::ResourceState{} : it->second.states.front();
}

graph::ResourceState PhysicalResources::importedState(const std::string& name) const {
  if (auto e = externalStates_.find(name); e != externalStates_.end() && !e->second.empty()) return e->second.front();
  auto it = persistent_.find(name);
  return it == persistent_.end() || it->second.states.empty() ? graph::ResourceState{} : it->second.states.front();
}

PhysicalResources::Persistent& PhysicalResources::persistent(const graph::ResourceDecl& decl) {
  if (decl.kind == graph::ResourceKind::History) historyParity_.try_emplace(decl.historyBase, 0);
  auto& p = persistent_[physicalKey(decl)];
  if (decl.isBuffer()) {
    if (p.buffer.buffer && p.buffer.size != decl.buffer.bytes) destroy(p), p = {};
    if (!p.buffer.buffer) p.buffer = createDeviceBuffer(vk_, decl.buffer.bytes, kPersistentBufferUsage);
  } else {
    if (p.image.image && !sameShape(p.image, decl.desc)) destroy(p), p = {};
    if (!p.image.image) p.image = createImage(vk_, shapeOf(decl.desc), kPersistentUsage);
  }
  return p;
}

std::vector<graph::PhysicalResource> PhysicalResources::prepare(const graph::RenderGraph& graph,
                                                                const graph::CompiledGraph& compiled) {
  prepareTransients(graph, compiled);
  std::vector<graph::PhysicalResource> out(graph.resources().size());
  for (graph::ResourceId id = 0; id < out.size(); ++id) {
    const auto& decl = graph.resources()[id];
    if (!compiled.resources[id].used) continue;
    if (decl.externalImage || decl.externalBuffer) {
      out[id] = {decl.externalImage, decl.externalBuffer};
    } else if (decl.kind == graph::ResourceKind::Transient) {
      if (decl.isBuffer()) out[id].buffer = &transientBuffers_.at(decl.name);
      else out[id].image = &transientImages_.at(decl.name);
    } else {
      Persistent& p = persistent(decl);
      out[id] = decl.isBuffer() ? graph::PhysicalResource{nullptr, &p.buffer} : graph::PhysicalResource{&p.image, nullptr};
    }
  }
  return out;
}

void PhysicalResources::prepareTransients(const graph::RenderGraph& graph, const graph::CompiledGraph& compiled) {
  std::string signature;
  for (graph::ResourceId id = 0; id < graph.resources().size(); ++id) {
    const auto& decl = graph.resources()[id];
    const auto& res = compiled.resources[id];
    if (decl.kind != graph::ResourceKind::Transient || !res.used) continue;
    signature += fmt::format("{}:{}x{}x{}x{}:{}:{}:{}:{}:{};", decl.name, decl.desc.width, decl.desc.height,
                             decl.desc.mipLevels, decl.desc.arrayLayers, int(decl.desc.format), decl.buffer.bytes,
                             res.usage, res.bufferUsage, res.memorySlot);
  }
  if (signature == transientSignature_) return;
  releaseTransients();
  transientSignature_ = signature;

  struct SlotNeed {
    VkDeviceSize size = 0, alignment = 1;
    uint32_t typeBits = ~0u;
  };
  std::vector<SlotNeed> needs(compiled.slots.size());
  auto need = [&](graph::ResourceId id, const VkMemoryRequirements& req) {
    auto& n = needs.at(size_t(compiled.resources[id].memorySlot));
    n.size = std::max(n.size, req.size);
    n.alignment = std::max(n.alignment, req.alignment);
    n.typeBits &= req.memoryTypeBits;
  };
  std::vector<std::pair<graph::ResourceId, GpuImage>> images;
  std::vector<std::pair<graph::ResourceId, GpuBuffer>> buffers;
  for (graph::ResourceId id = 0; id < graph.resources().size(); ++id) {
    const auto& decl = graph.resources()[id];
    const auto& res = compiled.resources[id];
    if (decl.kind != graph::ResourceKind::Transient || !res.used) continue;
    VkMemoryRequirements req;
    if (decl.isBuffer()) {
      GpuBuffer buffer = createBufferUnbound(vk_, decl.buffer.bytes, res.bufferUsage);
      vkGetBufferMemoryRequirements(vk_.device, buffer.buffer, &req);
      buffers.emplace_back(id, buffer);
    } else {
      GpuImage image = createImageUnbound(vk_, shapeOf(decl.desc), res.usage);
      vkGetImageMemoryRequirements(vk_.device, image.image, &req);
      images.emplace_back(id, image);
    }
    need(id, req);
  }
  for (const auto& n : needs) slots_.push_back(allocateDeviceMemory(vk_, n.size, n.typeBits));
  auto slotOf = [&](graph::ResourceId id) { return slots_[size_t(compiled.resources[id].memorySlot)].memory; };
  for (auto& [id, image] : images) {
    bindImage(vk_, image, slotOf(id), 0);
    transientImages_[graph.resources()[id].name] = image;
  }
  for (auto& [id, buffer] : buffers) {
    bindBuffer(vk_, buffer, slotOf(id), 0);
    transientBuffers_[graph.resources()[id].name] = buffer;
  }
}

void PhysicalResources::releaseTransients() {
  for (auto& [name, image] : transientImages_) destroyImage(vk_, image);  // aliased images own no memory
  for (auto& [name, buffer] : transientBuffers_) destroyBuffer(vk_, buffer);
  for (auto& slot : slots_) freeMemory(vk_, slot);
  transientImages_.clear();
  transientBuffers_.clear();
  slots_.clear();
  transientSignature_.clear();
}

void PhysicalResources::keepFinalStates(const graph::RenderGraph& graph, const graph::CompiledGraph& compiled) {
  for (graph::ResourceId id = 0; id < graph.resources().size(); ++id) {
    const auto& decl = graph.resources()[id];
    if (decl.kind == graph::ResourceKind::Transient || !compiled.resources[id].used) continue;
    if (decl.externalImage || decl.externalBuffer)
      externalStates_[decl.name] = compiled.resources[id].finalStates;
    else
      persistent_.at(physicalKey(decl)).states = compiled.resources[id].finalStates;
  }
}

void PhysicalResources::swapHistory() {
  for (auto& [base, parity] : historyParity_) parity = 1 - parity;
}

void PhysicalResources::dropHistory() {
  for (auto it = persistent_.begin(); it != persistent_.end();) {
    if (it->first.find('#') != std::string::npos) {
      destroy(it->second);
      it = persistent_.erase(it);
    } else {
      ++it;
    }
  }
  historyParity_.clear();
}

}  // namespace aor
