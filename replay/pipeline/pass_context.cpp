#include "pipeline/pass_context.h"

#include <stdexcept>

#include "common.h"

namespace aor::graph {

const GpuImage& PassContext::image(ResourceId id) const {
  if (id >= images.size() || !images[id]) throw std::logic_error("pass touched a resource it did not declare");
  return *images[id];
}

VkImageLayout PassContext::layout(ResourceId id) const {
  if (!pass) throw std::logic_error("no pass is being recorded");
  return requiredState(*pass, id).layout;
}

}  // namespace aor::graph

namespace aor {

void dispatchCompute(graph::PassContext& ctx, const ComputePipeline& pipeline, std::initializer_list<graph::ResourceId> images,
                     const void* pushConstants, uint32_t width, uint32_t height) {
  if (images.size() != pipeline.bindings.size()) throw std::logic_error("dispatch binds a different number of images than the pipeline declares");
  std::vector<VkDescriptorImageInfo> infos;
  infos.reserve(images.size());
  std::vector<VkWriteDescriptorSet> writes;
  uint32_t binding = 0;
  for (graph::ResourceId id : images) {
    VkDescriptorType type = pipeline.bindings[binding];
    VkSampler sampler = type == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE ? VK_NULL_HANDLE : ctx.vk.nearestSampler;
    infos.push_back({sampler, ctx.image(id).view, ctx.layout(id)});
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstBinding = binding++;
    write.descriptorCount = 1;
    write.descriptorType = type;
    write.pImageInfo = &infos.back();
    writes.push_back(write);
  }
  vkCmdBindPipeline(ctx.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.pipeline);
  ctx.vk.cmdPushDescriptorSet(ctx.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.layout, 0, uint32_t(writes.size()),
                              writes.data());
  if (pipeline.pushConstantSize)
    vkCmdPushConstants(ctx.cmd, pipeline.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, pipeline.pushConstantSize, pushConstants);
  uint32_t groups = pipeline.workgroupSize;
  if (groups == 0) throw std::logic_error("pipeline has no workgroup size");
  vkCmdDispatch(ctx.cmd, (width + groups - 1) / groups, (height + groups - 1) / groups, 1);
}

}  // namespace aor
