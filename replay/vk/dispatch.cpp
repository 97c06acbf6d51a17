#include "vk/dispatch.h"

#include <stdexcept>
#include <vector>

#include <fmt/format.h>

#include "vk/context.h"
#include "vk/resources.h"

namespace aor {

DispatchGroups groupsFor(const ComputePipeline& pipeline, uint32_t x, uint32_t y, uint32_t z) {
  auto groups = [](uint32_t n, uint32_t size) { return (n + size - 1) / size; };
  return {groups(x, pipeline.localSize[0]), groups(y, pipeline.localSize[1]), groups(z, pipeline.localSize[2])};
}

void recordDispatch(VulkanContext& vk, VkCommandBuffer cmd, const ComputePipeline& pipeline,
                    std::span<const BoundResource> bindings, const void* pushConstants, DispatchGroups groups,
                    const BoundResource* opCounts) {
  const auto& declared = pipeline.shader.bindings;
  if (bindings.size() != declared.size())
    throw std::logic_error(fmt::format("dispatch binds {} resources; the shader declares {}", bindings.size(), declared.size()));
  if ((pipeline.shader.opCounterBinding >= 0) != (opCounts != nullptr))
    throw std::logic_error(opCounts ? "a counter slot for a pipeline that does not count" : "a counting pipeline without a counter slot");
  std::vector<VkDescriptorImageInfo> images(bindings.size());
  std::vector<VkDescriptorBufferInfo> buffers(bindings.size() + 1);
  std::vector<VkWriteDescriptorSetAccelerationStructureKHR> structures(bindings.size());
  std::vector<VkWriteDescriptorSet> writes;
  for (uint32_t i = 0; i < bindings.size(); ++i) {
    const BoundResource& r = bindings[i];
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstBinding = i;
    write.descriptorCount = 1;
    write.descriptorType = declared[i].type;
    switch (declared[i].type) {
      case VK_DESCRIPTOR_TYPE_STORAGE_IMAGE:
      case VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE:
      case VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER: {
        bool sampler = declared[i].type == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        images[i] = {sampler ? (r.sampler ? r.sampler : vk.nearestSampler) : VK_NULL_HANDLE, r.view, r.layout};
        write.pImageInfo = &images[i];
        break;
      }
      case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER:
      case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER:
        buffers[i] = {r.buffer, r.offset, r.range};
        write.pBufferInfo = &buffers[i];
        break;
      case VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR:
        if (!r.accelerationStructure)
          throw std::logic_error(fmt::format("binding {} ('{}') gets no acceleration structure", i, declared[i].name));
        structures[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET_ACCELERATION_STRUCTURE_KHR};
        structures[i].accelerationStructureCount = 1;
        structures[i].pAccelerationStructures = &r.accelerationStructure;
        write.pNext = &structures[i];
        break;
      default:
        throw std::logic_error(fmt::format("binding {} ('{}') is a {}, which dispatches cannot bind", i, declared[i].name,
                                           descriptorTypeName(declared[i].type)));
    }
    writes.push_back(write);
  }
  if (opCounts) {
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstBinding = uint32_t(pipeline.shader.opCounterBinding);
    write.descriptorCount = 1;
    write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    buffers.back() = {opCounts->buffer, opCounts->offset, opCounts->range};
    write.pBufferInfo = &buffers.back();
    writes.push_back(write);
  }
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.pipeline);
  if (!writes.empty())
    vk.cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.layout, 0, uint32_t(writes.size()), writes.data());
  if (pipeline.shader.pushConstantBytes)
    vkCmdPushConstants(cmd, pipeline.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, pipeline.shader.pushConstantBytes, pushConstants);
  vkCmdDispatch(cmd, groups.x, groups.y, groups.z);
}

}  // namespace aor
