#include "vk/device_limits.h"

#include <fmt/format.h>

namespace aor {
namespace {

std::optional<std::string> over(uint64_t value, uint64_t limit, const char* what) {
  if (value <= limit) return std::nullopt;
  return fmt::format("{} {} (the device allows {})", value, what, limit);
}

uint32_t countOf(const ShaderInterface& shader, VkDescriptorType type) {
  uint32_t n = 0;
  for (const auto& b : shader.bindings) n += b.type == type;
  return n;
}

}  // namespace

DeviceLimits readDeviceLimits(VkPhysicalDevice device) {
  VkPhysicalDevicePushDescriptorPropertiesKHR push{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PUSH_DESCRIPTOR_PROPERTIES_KHR};
  VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &push};
  vkGetPhysicalDeviceProperties2(device, &props);
  const VkPhysicalDeviceLimits& l = props.properties.limits;
  DeviceLimits out;
  out.maxPushDescriptors = push.maxPushDescriptors;
  out.maxPerStageResources = l.maxPerStageResources;
  out.maxPerStageStorageImages = l.maxPerStageDescriptorStorageImages;
  out.maxPerStageSampledImages = l.maxPerStageDescriptorSampledImages;
  out.maxPerStageSamplers = l.maxPerStageDescriptorSamplers;
  out.maxPerStageUniformBuffers = l.maxPerStageDescriptorUniformBuffers;
  out.maxPerStageStorageBuffers = l.maxPerStageDescriptorStorageBuffers;
  out.maxPushConstantsSize = l.maxPushConstantsSize;
  out.maxUniformBufferRange = l.maxUniformBufferRange;
  out.maxComputeSharedMemorySize = l.maxComputeSharedMemorySize;
  for (int d = 0; d < 3; ++d) out.maxComputeWorkGroupSize[d] = l.maxComputeWorkGroupSize[d];
  out.maxComputeWorkGroupInvocations = l.maxComputeWorkGroupInvocations;
  return out;
}

std::optional<std::string> exceededLimit(const ShaderInterface& shader, const std::array<uint32_t, 3>& localSize,
                                         const DeviceLimits& limits) {
  const uint32_t descriptors = uint32_t(shader.bindings.size()) + (shader.opCounterBinding >= 0 ? 1 : 0);
  const uint32_t combined = countOf(shader, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);
  const uint64_t invocations = uint64_t(localSize[0]) * localSize[1] * localSize[2];
  const std::optional<std::string> checks[] = {
      over(descriptors, limits.maxPushDescriptors, "push descriptors"),
      over(descriptors, limits.maxPerStageResources, "resources in one stage"),
      over(countOf(shader, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE), limits.maxPerStageStorageImages, "storage images"),
      over(countOf(shader, VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE) + combined, limits.maxPerStageSampledImages, "sampled images"),
      over(combined, limits.maxPerStageSamplers, "samplers"),
      over(countOf(shader, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER), limits.maxPerStageUniformBuffers, "uniform buffers"),
      over(countOf(shader, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER) + (shader.opCounterBinding >= 0 ? 1 : 0),
           limits.maxPerStageStorageBuffers, "storage buffers"),
      over(shader.pushConstantBytes, limits.maxPushConstantsSize, "bytes of push constants"),
      over(shader.workgroupMemoryBytes, limits.maxComputeSharedMemorySize, "bytes of shared memory"),
      over(localSize[0], limits.maxComputeWorkGroupSize[0], "invocations in a workgroup's x"),
      over(localSize[1], limits.maxComputeWorkGroupSize[1], "invocations in a workgroup's y"),
      over(localSize[2], limits.maxComputeWorkGroupSize[2], "invocations in a workgroup's z"),
      over(invocations, limits.maxComputeWorkGroupInvocations, "invocations in a workgroup"),
  };
  for (const auto& c : checks)
    if (c) return c;
  return std::nullopt;
}

}  // namespace aor
