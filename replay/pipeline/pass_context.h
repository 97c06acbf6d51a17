#pragma once
// What a pass's execute callback gets from the executor: the command buffer and the physical
// image of every graph resource. Passes record only their own work; barriers are the executor's.
#include <initializer_list>
#include <vector>

#include "graph/render_graph.h"
#include "vk/context.h"
#include "vk/resources.h"

namespace aor::graph {

struct PassContext {
  VulkanContext& vk;
  VkCommandBuffer cmd;
  std::vector<const GpuImage*> images;  // indexed by ResourceId; null for unused resources
  const PassDecl* pass = nullptr;       // the pass being recorded
  const GpuImage& image(ResourceId id) const;
  // The layout the graph's barriers left `id` in for this pass: what its descriptors must say.
  VkImageLayout layout(ResourceId id) const;
};

}  // namespace aor::graph

namespace aor {

// recordDispatch (vk/dispatch.h) with binding i = images[i], in the layout the graph's barriers
// left it in for this pass.
void dispatchCompute(graph::PassContext& ctx, const ComputePipeline& pipeline, std::initializer_list<graph::ResourceId> images,
                     const void* pushConstants, uint32_t width, uint32_t height);

}  // namespace aor
