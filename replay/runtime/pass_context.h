#pragma once
// What a pass's execute callback gets from the graph's runtime: the command buffer and the physical
// image or buffer of every graph resource. Passes record only their own work; barriers are the
// executor's. dispatchCompute binds a pass's resources to its pipeline by the pipeline's reflected
// bindings, in the views and layouts the graph's barriers left.
#include <initializer_list>
#include <span>
#include <stdexcept>
#include <vector>

#include "graph/render_graph.h"
#include "vk/context.h"
#include "vk/dispatch.h"
#include "vk/resources.h"

namespace aor::graph {

struct PhysicalResource {
  const GpuImage* image = nullptr;
  const GpuBuffer* buffer = nullptr;
};

struct PassContext {
  VulkanContext& vk;
  VkCommandBuffer cmd;
  const RenderGraph& graph;
  std::vector<PhysicalResource> resources;  // indexed by ResourceId; null for unused resources
  const PassDecl* pass = nullptr;           // the pass being recorded
  const CompiledPass* compiled = nullptr;
  const GpuImage& image(ResourceId id) const;
  const GpuBuffer& buffer(ResourceId id) const;
  // Whether this pass really touches `id`: false for a writeIfRead nobody reads (and for resources
  // it never declared).
  bool has(ResourceId id) const;
  // The layout the graph's barriers left `range` of `id` in for this pass: what its descriptors must
  // say. Throws when the levels and layers in `range` are in different layouts.
  VkImageLayout layout(ResourceId id, Subresources range = {}) const;
};

}  // namespace aor::graph

namespace aor {

// One binding of a dispatch: a resource, the levels and layers bound (default: all), and for
// samplers whether to filter linearly (default: nearest, clamped to the edge).
struct Bind {
  graph::ResourceId id;
  graph::Subresources range{};
  bool linear = false;
  Bind(graph::ResourceId resource) : id(resource) {}  // NOLINT: a bare id binds the whole resource
  Bind(graph::ResourceId resource, graph::Subresources levels, bool linearFilter = false)
      : id(resource), range(levels), linear(linearFilter) {}
};

// recordDispatch (vk/dispatch.h) with binding i = bindings[i]. Each binding must match a live access
// the pass declared (a storage image or buffer a storage access, a sampler a sampled read, a uniform
// buffer a uniform read) and the shader's type for it; a mismatch is a logic error naming both.
// `pushConstants` must hold the shader's push-constant block (its size is reflected).
void dispatchCompute(graph::PassContext& ctx, const ComputePipeline& pipeline, std::span<const Bind> bindings,
                     const void* pushConstants, size_t pushBytes, DispatchGroups groups);
inline void dispatchCompute(graph::PassContext& ctx, const ComputePipeline& pipeline, std::initializer_list<Bind> bindings,
                            const void* pushConstants, size_t pushBytes, DispatchGroups groups) {
  dispatchCompute(ctx, pipeline, std::span<const Bind>(bindings.begin(), bindings.size()), pushConstants, pushBytes, groups);
}

// The same over a grid of invocations (one per pixel, usually), in whole workgroups.
template <typename Constants>
void dispatchCompute(graph::PassContext& ctx, const ComputePipeline& pipeline, std::initializer_list<Bind> bindings,
                     const Constants* pushConstants, uint32_t invocationsX, uint32_t invocationsY) {
  dispatchCompute(ctx, pipeline, bindings, pushConstants, sizeof(Constants), groupsFor(pipeline, invocationsX, invocationsY));
}
inline void dispatchCompute(graph::PassContext& ctx, const ComputePipeline& pipeline, std::initializer_list<Bind> bindings,
                            std::nullptr_t, uint32_t invocationsX, uint32_t invocationsY) {
  dispatchCompute(ctx, pipeline, bindings, nullptr, 0, groupsFor(pipeline, invocationsX, invocationsY));
}

}  // namespace aor
