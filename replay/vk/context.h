#pragma once
// Headless Vulkan instance + device with one compute queue. Lavapipe is the default device so the
// tool runs on any machine; --device picks another by index or name substring.
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "vk/device_limits.h"

namespace aor {

class OpCounter;

struct DeviceInfo;

// Device extensions the context can enable beyond its base set, with their features, when a run
// asks for them (ContextOptions::optionalExtensions): the ray-query path of rtao.
inline constexpr const char* kRayQueryExtension = "VK_KHR_ray_query";
inline constexpr const char* kAccelerationStructureExtension = "VK_KHR_acceleration_structure";

struct ContextOptions {
  std::string deviceSelector;  // empty: lavapipe if present, else the first device
  bool validate = false;       // Khronos validation with synchronization validation
  // Optional extensions the command's work would use on the chosen device (a technique's settings
  // decide, Technique::deviceExtensions); the context enables those the device offers with their
  // features, and no others, so a run that does not need them keeps the base device. Empty: none.
  std::function<std::vector<std::string>(const DeviceInfo& device)> optionalExtensions;
};

struct DeviceInfo {
  uint32_t index = 0;
  std::string name;
  std::string driver;      // driver name, e.g. "llvmpipe"
  std::string driverInfo;  // the driver's version text, e.g. "Mesa 22.3.6 (LLVM 15.0.6)"
  std::string apiVersion;
  bool isLavapipe = false;
  bool isCpu = false;  // a CPU implementation (lavapipe, llvmpipe, SwiftShader): it computes on the host's cores
  std::vector<std::string> extensions;  // every device extension the driver offers
  DeviceLimits limits;
  bool hasExtension(const std::string& name) const;
};

struct VulkanContext {
  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  uint32_t queueFamily = 0;
  VkCommandPool commandPool = VK_NULL_HANDLE;
  VkSampler nearestSampler = VK_NULL_HANDLE;  // clamp to edge, every mip level
  VkSampler linearSampler = VK_NULL_HANDLE;
  PFN_vkCmdPushDescriptorSetKHR cmdPushDescriptorSet = nullptr;
  VkPhysicalDeviceMemoryProperties memoryProperties{};
  DeviceInfo info;
  std::vector<std::string> enabledOptionalExtensions;  // those of ContextOptions::optionalExtensions enabled
  bool enabled(const std::string& extension) const;
  double timestampPeriodNs = 1.0;
  uint32_t timestampValidBits = 64;
  // Set while a replay counts its passes' work (vk/op_counter.h): pipelines come from the counting
  // build and every dispatch gets a counter slot. Owned by whoever set it.
  OpCounter* opCounter = nullptr;
  // Counted cost (cost/callgrind_counter.h): after every fence wait, 2 ms for a CPU device's queue
  // thread to finish what follows the signal, so it never races this thread for the heap.
  bool settleAfterSubmit = false;

  // Validation messages (warnings and errors); any one fails a --validate run.
  std::mutex messageMutex;
  std::vector<std::string> validationMessages;
  size_t validationMessageCount();
};

std::vector<DeviceInfo> listDevices();
// The Vulkan loader's instance version, "1.3.239".
std::string loaderVersion();
// Runs one recorded command buffer on the context's queue and waits for it; `fence` is unsignalled
// before and after.
void submitAndWait(const VulkanContext& context, VkCommandBuffer cmd, VkFence fence);
// Records `record` into a one-time command buffer of the context's pool, runs it and waits: set-up
// work (uploads, acceleration-structure builds) that has finished when this returns.
void runOneTimeCommands(const VulkanContext& context, const std::function<void(VkCommandBuffer)>& record);
// Milliseconds between two timestamp-query values, wrapping within the queue's valid bits.
double timestampDeltaMs(const VulkanContext& context, uint64_t from, uint64_t to);
// Throws NoDeviceError when no device (or none matching the selector) exists.
void createContext(VulkanContext& context, const ContextOptions& options);
void destroyContext(VulkanContext& context);

// Owns the Vulkan context for one command (or benchmark harness): created on construction,
// destroyed at the end of the scope. A command that must count the last validation messages
// before deciding whether it succeeded calls destroyContext(vk) itself; the destructor then finds
// nothing left to destroy.
struct ContextScope {
  VulkanContext vk;
  explicit ContextScope(const ContextOptions& options) { createContext(vk, options); }
  ~ContextScope() { destroyContext(vk); }
};

}  // namespace aor
