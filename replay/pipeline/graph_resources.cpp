#include "pipeline/graph_resources.h"

#include <fmt/format.h>

#include "vk/context.h"

namespace aor {
namespace {

constexpr VkImageUsageFlags kPersistentUsage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_STORAGE_BIT |
                                               VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;

}  // namespace

GraphResources::~GraphResources() {
  releaseTransients();
  for (auto& [name, p] : persistent_) destroyImage(vk_, p.image);
}

std::string GraphResources::historyKey(const std::string& base, bool current) const {
  auto parity = historyParity_.count(base) ? historyParity_.at(base) : 0;
  return fmt::format("{}#{}", base, current ? parity : 1 - parity);
}

std::string GraphResources::physicalKey(const graph::ResourceDecl& decl) const {
  return decl.kind == graph::ResourceKind::History ? historyKey(decl.historyBase, decl.historyCurrent) : decl.name;
}

graph::ImageState GraphResources::historyState(const std::string& base, bool current) const {
  auto it = persistent_.find(historyKey(base, current));
  return it == persistent_.end() ? graph::ImageState{} : it->second.state;
}

GraphResources::Persistent& GraphResources::persistent(const graph::ResourceDecl& decl) {
  if (decl.kind == graph::ResourceKind::History) historyParity_.try_emplace(decl.historyBase, 0);
  auto& p = persistent_[physicalKey(decl)];
  const auto& d = decl.desc;
  if (p.image.image && (p.image.width != d.width || p.image.height != d.height || p.image.format != d.format)) {
    destroyImage(vk_, p.image);
    p = {};
  }
  if (!p.image.image) p.image = createImage(vk_, d.width, d.height, d.format, kPersistentUsage);
  return p;
}

std::vector<const GpuImage*> GraphResources::prepare(const graph::RenderGraph& graph, const graph::CompiledGraph& compiled) {
  prepareTransients(graph, compiled);
  std::vector<const GpuImage*> images(graph.resources().size(), nullptr);
  for (graph::ResourceId id = 0; id < images.size(); ++id) {
    const auto& decl = graph.resources()[id];
    if (!compiled.resources[id].used) continue;
    images[id] = decl.kind == graph::ResourceKind::Transient ? &transients_.at(decl.name) : &persistent(decl).image;
  }
  return images;
}

void GraphResources::prepareTransients(const graph::RenderGraph& graph, const graph::CompiledGraph& compiled) {
  std::string signature;
  for (graph::ResourceId id = 0; id < graph.resources().size(); ++id) {
    const auto& decl = graph.resources()[id];
    const auto& res = compiled.resources[id];
    if (decl.kind != graph::ResourceKind::Transient || !res.used) continue;
    signature += fmt::format("{}:{}x{}:{}:{}:{};", decl.name, decl.desc.width, decl.desc.height, int(decl.desc.format),
                             res.usage, res.memorySlot);
  }
  if (signature == transientSignature_) return;
  releaseTransients();
  transientSignature_ = signature;

  struct SlotNeed {
    VkDeviceSize size = 0, alignment = 1;
    uint32_t typeBits = ~0u;
  };
  std::vector<SlotNeed> needs(compiled.slots.size());
  std::vector<std::pair<graph::ResourceId, GpuImage>> created;
  for (graph::ResourceId id = 0; id < graph.resources().size(); ++id) {
    const auto& decl = graph.resources()[id];
    const auto& res = compiled.resources[id];
    if (decl.kind != graph::ResourceKind::Transient || !res.used) continue;
    GpuImage image = createImageUnbound(vk_, decl.desc.width, decl.desc.height, decl.desc.format, res.usage);
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(vk_.device, image.image, &req);
    auto& need = needs.at(size_t(res.memorySlot));
    need.size = std::max(need.size, req.size);
    need.alignment = std::max(need.alignment, req.alignment);
    need.typeBits &= req.memoryTypeBits;
    created.emplace_back(id, image);
  }
  for (const auto& need : needs) slots_.push_back(allocateDeviceMemory(vk_, need.size, need.typeBits));
  for (auto& [id, image] : created) {
    bindImage(vk_, image, slots_[size_t(compiled.resources[id].memorySlot)].memory, 0);
    transients_[graph.resources()[id].name] = image;
  }
}

void GraphResources::releaseTransients() {
  for (auto& [name, image] : transients_) destroyImage(vk_, image);  // aliased images own no memory
  for (auto& slot : slots_) freeMemory(vk_, slot);
  transients_.clear();
  slots_.clear();
  transientSignature_.clear();
}

void GraphResources::keepFinalStates(const graph::RenderGraph& graph, const graph::CompiledGraph& compiled) {
  for (graph::ResourceId id = 0; id < graph.resources().size(); ++id) {
    const auto& decl = graph.resources()[id];
    if (decl.kind == graph::ResourceKind::Transient || !compiled.resources[id].used) continue;
    persistent_.at(physicalKey(decl)).state = compiled.resources[id].finalState;
  }
}

void GraphResources::swapHistory() {
  for (auto& [base, parity] : historyParity_) parity = 1 - parity;
}

void GraphResources::dropHistory() {
  for (auto it = persistent_.begin(); it != persistent_.end();) {
    if (it->first.find('#') != std::string::npos) {
      destroyImage(vk_, it->second.image);
      it = persistent_.erase(it);
    } else {
      ++it;
    }
  }
  historyParity_.clear();
}

}  // namespace aor
