#include "runtime/pass_context.h"

#include <fmt/format.h>

#include "vk/op_counter.h"

namespace aor::graph {

const GpuImage& PassContext::image(ResourceId id) const {
  if (id >= resources.size() || !resources[id].image) throw std::logic_error("pass touched an image it did not declare");
  return *resources[id].image;
}

const GpuBuffer& PassContext::buffer(ResourceId id) const {
  if (id >= resources.size() || !resources[id].buffer) throw std::logic_error("pass touched a buffer it did not declare");
  return *resources[id].buffer;
}

bool PassContext::has(ResourceId id) const {
  if (!pass || !compiled) return false;
  for (size_t a = 0; a < pass->accesses.size(); ++a)
    if (pass->accesses[a].resource == id && compiled->accessLive[a]) return true;
  return false;
}

VkImageLayout PassContext::layout(ResourceId id, Subresources range) const {
  if (!pass) throw std::logic_error("no pass is being recorded");
  const ResourceDecl& decl = graph.resources().at(id);
  Subresources r = range.resolve(decl.desc);
  VkImageLayout first = requiredState(*pass, id, Subresources{r.baseMip, 1, r.baseLayer, 1}).layout;
  for (uint32_t layer = r.baseLayer; layer < r.baseLayer + r.layerCount; ++layer)
    for (uint32_t mip = r.baseMip; mip < r.baseMip + r.mipCount; ++mip)
      if (requiredState(*pass, id, Subresources{mip, 1, layer, 1}).layout != first)
        throw std::logic_error(fmt::format("pass '{}' binds '{}'{} as one view, but its levels are in different layouts",
                                           pass->name, decl.name, rangeText(decl, r)));
  return first;
}

}  // namespace aor::graph

namespace aor {
namespace {

// Whether a declared access fits the descriptor type the shader gives the binding.
bool accessFits(graph::Access access, VkDescriptorType type) {
  using graph::Access;
  switch (type) {
    case VK_DESCRIPTOR_TYPE_STORAGE_IMAGE:
    case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER: return access == Access::StorageRead || access == Access::StorageWrite;
    case VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER:
    case VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE: return access == Access::SampledRead;
    case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER: return access == Access::UniformRead;
    case VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR: return access == Access::AccelerationStructureRead;
    default: return false;
  }
}

BoundResource bindOne(graph::PassContext& ctx, const ShaderBinding& binding, const Bind& bind, size_t index) {
  const graph::ResourceDecl& decl = ctx.graph.resources().at(bind.id);
  graph::Subresources range = decl.isBuffer() ? graph::Subresources{0, 1, 0, 1} : bind.range.resolve(decl.desc);
  bool declared = false;
  for (size_t a = 0; a < ctx.pass->accesses.size(); ++a) {
    const auto& access = ctx.pass->accesses[a];
    declared |= access.resource == bind.id && ctx.compiled->accessLive[a] && accessFits(access.access, binding.type) &&
                graph::overlaps(access.range, range);
  }
  if (!declared)
    throw std::logic_error(fmt::format("pass '{}' binds '{}'{} to binding {} ('{}', a {}) without declaring a matching access",
                                       ctx.pass->name, decl.name, rangeText(decl, range), index, binding.name,
                                       descriptorTypeName(binding.type)));
  BoundResource r;
  if (decl.isBuffer()) {
    r.buffer = ctx.buffer(bind.id).buffer;
    r.accelerationStructure = ctx.buffer(bind.id).accelerationStructure;
    return r;
  }
  const GpuImage& image = ctx.image(bind.id);
  r.view = imageViewOf(ctx.vk, image, {range.baseMip, range.mipCount, range.baseLayer, range.layerCount, binding.arrayed});
  r.layout = ctx.layout(bind.id, range);
  r.sampler = bind.linear ? ctx.vk.linearSampler : ctx.vk.nearestSampler;
  return r;
}

// What a counted dispatch reads and writes of its bindings (vk/op_counter.h): each bound
// subresource once, read when a live access of the pass reads it, written when one writes it.
struct BoundBytes {
  uint64_t read = 0, written = 0;
};
BoundBytes boundBytes(const graph::PassContext& ctx, std::span<const Bind> bindings) {
  BoundBytes out;
  for (const Bind& bind : bindings) {
    const graph::ResourceDecl& decl = ctx.graph.resources().at(bind.id);
    uint64_t bytes = decl.buffer.bytes;
    graph::Subresources range{0, 1, 0, 1};
    if (!decl.isBuffer()) {
      range = bind.range.resolve(decl.desc);
      graph::ImageDesc part{std::max(1u, decl.desc.width >> range.baseMip), std::max(1u, decl.desc.height >> range.baseMip),
                            decl.desc.format, range.mipCount, range.layerCount};
      bytes = graph::imageBytes(part);
    }
    bool reads = false, writes = false;
    for (size_t a = 0; a < ctx.pass->accesses.size(); ++a) {
      const auto& access = ctx.pass->accesses[a];
      if (access.resource != bind.id || !ctx.compiled->accessLive[a] || !graph::overlaps(access.range, range)) continue;
      writes |= access.access == graph::Access::StorageWrite;
      reads |= access.access != graph::Access::StorageWrite;
    }
    out.read += reads ? bytes : 0;
    out.written += writes ? bytes : 0;
  }
  return out;
}

}  // namespace

void dispatchCompute(graph::PassContext& ctx, const ComputePipeline& pipeline, std::span<const Bind> bindings,
                     const void* pushConstants, size_t pushBytes, DispatchGroups groups) {
  const auto& declared = pipeline.shader.bindings;
  if (bindings.size() != declared.size())
    throw std::logic_error(fmt::format("pass '{}' binds {} resources; its shader declares {}", ctx.pass->name,
                                       bindings.size(), declared.size()));
  if (pushBytes < pipeline.shader.pushConstantBytes)
    throw std::logic_error(fmt::format("pass '{}' pushes {} bytes of constants; its shader reads {}", ctx.pass->name,
                                       pushBytes, pipeline.shader.pushConstantBytes));
  std::vector<BoundResource> bound;
  bound.reserve(bindings.size());
  size_t i = 0;
  for (const Bind& b : bindings) {
    bound.push_back(bindOne(ctx, declared[i], b, i));
    ++i;
  }
  if (pipeline.shader.opCounterBinding < 0) {
    recordDispatch(ctx.vk, ctx.cmd, pipeline, bound, pushConstants, groups);
    return;
  }
  if (!ctx.vk.opCounter) throw std::logic_error(fmt::format("pass '{}' records a counting pipeline outside a counted replay", ctx.pass->name));
  BoundBytes bytes = boundBytes(ctx, bindings);
  uint64_t invocations = uint64_t{groups.x} * groups.y * groups.z * pipeline.localSize[0] * pipeline.localSize[1] * pipeline.localSize[2];
  BoundResource slot = ctx.vk.opCounter->slot(ctx.pass->name, bytes.read, bytes.written, invocations);
  recordDispatch(ctx.vk, ctx.cmd, pipeline, bound, pushConstants, groups, &slot);
}

}  // namespace aor
