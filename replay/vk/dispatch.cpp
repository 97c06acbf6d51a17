#include "vk/dispatch.h"

#include <stdexcept>
#include <vector>

#include "vk/context.h"
#include "vk/resources.h"

namespace aor {

void recordDispatch(VulkanContext& vk, VkCommandBuffer cmd, const ComputePipeline& pipeline,
                    std::span<const BoundImage> images, const void* pushConstants, uint32_t width, uint32_t height) {
  if (images.size() != pipeline.bindings.size()) throw std::logic_error("dispatch binds a different number of images than the pipeline declares");
  std::vector<VkDescriptorImageInfo> infos;
  infos.reserve(images.size());
  std::vector<VkWriteDescriptorSet> writes;
  uint32_t binding = 0;
  for (const BoundImage& image : images) {
    VkDescriptorType type = pipeline.bindings[binding];
    VkSampler sampler = type == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE ? VK_NULL_HANDLE : vk.nearestSampler;
    infos.push_back({sampler, image.view, image.layout});
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstBinding = binding++;
    write.descriptorCount = 1;
    write.descriptorType = type;
    write.pImageInfo = &infos.back();
    writes.push_back(write);
  }
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.pipeline);
  vk.cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.layout, 0, uint32_t(writes.size()), writes.data());
  if (pipeline.pushConstantSize)
    vkCmdPushConstants(cmd, pipeline.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, pipeline.pushConstantSize, pushConstants);
  uint32_t groups = pipeline.workgroupSize;
  if (groups == 0) throw std::logic_error("pipeline has no workgroup size");
  vkCmdDispatch(cmd, (width + groups - 1) / groups, (height + groups - 1) / groups, 1);
}

}  // namespace aor
