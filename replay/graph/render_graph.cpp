// Graph building: resources, passes and the accesses they declare, checked as they are declared.
// Compilation is in compile.cpp.
#include "graph/render_graph.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

namespace aor::graph {
namespace {

bool imageOnly(Access access) { return access == Access::SampledRead; }
bool bufferOnly(Access access) {
  return access == Access::UniformRead || access == Access::IndirectRead || access == Access::AccelerationStructureRead;
}

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
  uint32_t largest = std::max(desc.width, desc.height);
  uint32_t maxLevels = 1;
  while (largest >>= 1) ++maxLevels;
  if (desc.mipLevels == 0 || desc.mipLevels > maxLevels || desc.arrayLayers == 0) {
    throw std::invalid_argument(fmt::format("image '{}' ({}x{}) cannot have {} mip levels and {} layers", name,
                                            desc.width, desc.height, desc.mipLevels, desc.arrayLayers));
  }
}

}  // namespace

Subresources Subresources::resolve(const ImageDesc& desc) const {
  Subresources r = *this;
  if (r.mipCount == kAll) r.mipCount = baseMip < desc.mipLevels ? desc.mipLevels - baseMip : 0;
  if (r.layerCount == kAll) r.layerCount = baseLayer < desc.arrayLayers ? desc.arrayLayers - baseLayer : 0;
  return r;
}

bool overlaps(const Subresources& a, const Subresources& b) {
  bool mips = a.baseMip < b.baseMip + b.mipCount && b.baseMip < a.baseMip + a.mipCount;
  bool layers = a.baseLayer < b.baseLayer + b.layerCount && b.baseLayer < a.baseLayer + a.layerCount;
  return mips && layers;
}

void PassBuilder::read(ResourceId id, Access access, Subresources range) { declare(id, access, range, false, false); }

void PassBuilder::write(ResourceId id, Access access, Subresources range) { declare(id, access, range, true, false); }

void PassBuilder::writeIfRead(ResourceId id, Access access, Subresources range) {
  declare(id, access, range, true, true);
}

void PassBuilder::declare(ResourceId id, Access access, Subresources range, bool asWrite, bool ifRead) {
  PassDecl& pass = graph_.passes_.at(pass_);
  const char* verb = asWrite ? "writes" : "reads";
  if (id == kNoResource || id >= graph_.resources_.size()) {
    throw std::invalid_argument(fmt::format(
        "pass '{}' {} an invalid resource id ({})", pass.name, verb,
        id == kNoResource ? std::string("kNoResource") : std::to_string(id)));
  }
  const ResourceDecl& res = graph_.resources_[id];
  if (isWrite(access) != asWrite) {
    throw std::invalid_argument(fmt::format("pass '{}' {} '{}' with a {} access ({})", pass.name, verb, res.name,
                                            asWrite ? "read" : "write", accessName(access)));
  }
  if ((res.isBuffer() && imageOnly(access)) || (!res.isBuffer() && bufferOnly(access))) {
    throw std::invalid_argument(fmt::format("pass '{}' {} {} '{}' with a {} access", pass.name, verb,
                                            res.isBuffer() ? "buffer" : "image", res.name, accessName(access)));
  }
  Subresources resolved = res.isBuffer() ? Subresources{0, 1, 0, 1} : range.resolve(res.desc);
  bool inside = resolved.mipCount > 0 && resolved.layerCount > 0 &&
                resolved.baseMip + resolved.mipCount <= (res.isBuffer() ? 1 : res.desc.mipLevels) &&
                resolved.baseLayer + resolved.layerCount <= (res.isBuffer() ? 1 : res.desc.arrayLayers);
  if (!inside) {
    throw std::invalid_argument(fmt::format("pass '{}' {} mips {}+{} layers {}+{} of '{}', which has {} and {}",
                                            pass.name, verb, range.baseMip, range.mipCount, range.baseLayer,
                                            range.layerCount, res.name, res.desc.mipLevels, res.desc.arrayLayers));
  }
  pass.accesses.push_back(AccessDecl{id, access, resolved, ifRead});
}

void PassBuilder::sideEffect() { graph_.passes_.at(pass_).sideEffect = true; }

ResourceId RenderGraph::add(ResourceDecl decl) {
  resources_.push_back(std::move(decl));
  return static_cast<ResourceId>(resources_.size() - 1);
}

ResourceId RenderGraph::createImage(std::string name, ImageDesc desc) {
  validateDesc(name, desc);
  return add(ResourceDecl{std::move(name), desc, {}, ResourceType::Image, ResourceKind::Transient});
}

ResourceId RenderGraph::importImage(std::string name, ImageDesc desc, ResourceState initialState) {
  validateDesc(name, desc);
  return add(ResourceDecl{std::move(name), desc, {}, ResourceType::Image, ResourceKind::Imported, initialState});
}

ResourceId RenderGraph::createBuffer(std::string name, BufferDesc desc) {
  if (desc.bytes == 0) throw std::invalid_argument(fmt::format("buffer '{}' is empty", name));
  return add(ResourceDecl{std::move(name), {}, desc, ResourceType::Buffer, ResourceKind::Transient});
}

ResourceId RenderGraph::importBuffer(std::string name, BufferDesc desc, ResourceState initialState) {
  if (desc.bytes == 0) throw std::invalid_argument(fmt::format("buffer '{}' is empty", name));
  initialState.layout = VK_IMAGE_LAYOUT_UNDEFINED;
  return add(ResourceDecl{std::move(name), {}, desc, ResourceType::Buffer, ResourceKind::Imported, initialState});
}

ResourceId RenderGraph::importExternalImage(std::string name, ImageDesc desc, const GpuImage& image, ResourceState initialState) {
  ResourceId id = importImage(std::move(name), desc, initialState);
  resources_[id].externalImage = &image;
  return id;
}

ResourceId RenderGraph::importExternalBuffer(std::string name, BufferDesc desc, const GpuBuffer& buffer, ResourceState initialState) {
  ResourceId id = importBuffer(std::move(name), desc, initialState);
  resources_[id].externalBuffer = &buffer;
  return id;
}

HistoryPair RenderGraph::createHistory(std::string name, ImageDesc desc, bool previousValid,
                                       ResourceState previousState, ResourceState currentState) {
  validateDesc(name, desc);
  HistoryPair pair;
  auto history = [&](const char* half, ResourceState state, bool current) {
    return add(ResourceDecl{name + half, desc, {}, ResourceType::Image, ResourceKind::History, state, {}, nullptr, nullptr,
                            name, current});
  };
  if (previousValid) pair.previous = history(".previous", previousState, false);
  pair.current = history(".current", currentState, true);
  return pair;
}

void RenderGraph::setInitialStates(ResourceId id, std::vector<ResourceState> states) {
  ResourceDecl& res = resources_.at(id);
  if (res.kind == ResourceKind::Transient || states.size() != res.subresourceCount())
    throw std::invalid_argument(fmt::format("'{}': {} initial states for {} subresources of a {} resource", res.name,
                                            states.size(), res.subresourceCount(), kindName(res.kind)));
  res.initialStates = std::move(states);
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

RenderGraph RenderGraph::withoutRuntime() const {
  RenderGraph copy = *this;
  for (auto& pass : copy.passes_) pass.execute = {};
  for (auto& resource : copy.resources_) resource.externalImage = nullptr, resource.externalBuffer = nullptr;
  return copy;
}

GraphSnapshot snapshotOf(const RenderGraph& graph, const CompiledGraph& compiled) { return {graph.withoutRuntime(), compiled}; }

}  // namespace aor::graph
