#pragma once
// One compute dispatch of a ComputePipeline, its resources bound by push descriptors. The render
// graph's passes reach it through dispatchCompute (runtime/pass_context.h), which supplies the views
// and layouts the graph's barriers left; a harness without a graph (bench/dispatch_floor) calls it
// directly.
#include <span>

#include <vulkan/vulkan.h>

namespace aor {

struct VulkanContext;
struct ComputePipeline;

// What one binding of the pipeline's set 0 receives: an image view in a layout (storage and sampled
// images), a buffer range (storage and uniform buffers) or an acceleration structure, as the
// pipeline's reflected type says.
struct BoundResource {
  VkImageView view = VK_NULL_HANDLE;
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;  // the layout the image is in when the dispatch runs
  VkSampler sampler = VK_NULL_HANDLE;                // samplers: null means the context's nearest sampler
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceSize offset = 0, range = VK_WHOLE_SIZE;
  VkAccelerationStructureKHR accelerationStructure = VK_NULL_HANDLE;
};

struct DispatchGroups {
  uint32_t x = 1, y = 1, z = 1;
};
// Workgroups covering a grid of invocations with the pipeline's workgroup size.
DispatchGroups groupsFor(const ComputePipeline& pipeline, uint32_t invocationsX, uint32_t invocationsY,
                         uint32_t invocationsZ = 1);

// Binds `pipeline`, pushes the descriptors (binding i = bindings[i]) and push constants, and
// dispatches `groups`. A counting-build pipeline (vk/op_counter.h) also needs `opCounts`, its
// dispatch's counter slot.
void recordDispatch(VulkanContext& vk, VkCommandBuffer cmd, const ComputePipeline& pipeline,
                    std::span<const BoundResource> bindings, const void* pushConstants, DispatchGroups groups,
                    const BoundResource* opCounts = nullptr);

}  // namespace aor
