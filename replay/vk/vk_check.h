#pragma once
// One checking macro for every Vulkan call: a failure becomes a VulkanError naming the call.
#include <stdexcept>
#include <string>

#include <vulkan/vulkan.h>

namespace aor {

struct VulkanError : std::runtime_error {
  VulkanError(VkResult result, const char* call, const char* file, int line);
  VkResult result;
};

// No usable Vulkan device (exit code 3).
struct NoDeviceError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

const char* vkResultName(VkResult result);

}  // namespace aor

#define VK_CHECK(call)                                                         \
  do {                                                                         \
    VkResult vkCheckResult_ = (call);                                          \
    if (vkCheckResult_ != VK_SUCCESS)                                          \
      throw ::aor::VulkanError(vkCheckResult_, #call, __FILE__, __LINE__);     \
  } while (0)
