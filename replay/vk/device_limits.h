#pragma once
// The device limits a compute pass can reach, read once from the selected device, and the one
// check of a reflected shader against them. A technique's passes are checked before any GPU work
// (Technique::checkDeviceLimits), and every pipeline again when it is created, so a shader past a
// limit is refused by name instead of being invalid Vulkan (lavapipe crashes on 67 push
// descriptors where it allows 32).
#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include <vulkan/vulkan.h>

#include "vk/shader_reflection.h"

namespace aor {

struct DeviceLimits {
  uint32_t maxPushDescriptors = 0;
  uint32_t maxPerStageResources = 0;
  uint32_t maxPerStageStorageImages = 0, maxPerStageSampledImages = 0, maxPerStageSamplers = 0;
  uint32_t maxPerStageUniformBuffers = 0, maxPerStageStorageBuffers = 0;
  uint32_t maxPushConstantsSize = 0;
  uint32_t maxUniformBufferRange = 0;
  uint32_t maxComputeSharedMemorySize = 0;
  std::array<uint32_t, 3> maxComputeWorkGroupSize{};
  uint32_t maxComputeWorkGroupInvocations = 0;
};

// vkCmdUpdateBuffer's fixed limit (the Vulkan specification's, not a device's).
inline constexpr uint32_t kMaxUpdateBufferBytes = 65536;

DeviceLimits readDeviceLimits(VkPhysicalDevice device);

// The first limit `shader` (with workgroup size `localSize`) exceeds on a device with `limits`, as
// "67 push descriptors (the device allows 32)"; nullopt when it fits.
std::optional<std::string> exceededLimit(const ShaderInterface& shader, const std::array<uint32_t, 3>& localSize,
                                         const DeviceLimits& limits);

}  // namespace aor
