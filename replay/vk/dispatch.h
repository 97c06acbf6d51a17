#pragma once
// One compute dispatch of a ComputePipeline over a width x height grid of pixels, with its images
// bound by push descriptors. The render graph's passes reach it through dispatchCompute
// (pipeline/pass_context.h), which supplies the layouts the graph's barriers left; a harness
// without a graph (bench/dispatch_floor) calls it directly.
#include <span>

#include <vulkan/vulkan.h>

namespace aor {

struct VulkanContext;
struct ComputePipeline;

struct BoundImage {
  VkImageView view;
  VkImageLayout layout;  // the layout the image is in when the dispatch runs
};

// Binds `pipeline`, pushes the descriptors (binding i = images[i], of the type the pipeline's
// layout gives it: sampled images through the nearest sampler, storage images as they are) and
// push constants, and dispatches one workgroup per tile of the pipeline's workgroup size.
void recordDispatch(VulkanContext& vk, VkCommandBuffer cmd, const ComputePipeline& pipeline,
                    std::span<const BoundImage> images, const void* pushConstants, uint32_t width, uint32_t height);

}  // namespace aor
