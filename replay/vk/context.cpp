#include "vk/context.h"

#include <time.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include <fmt/format.h>

#include "vk/device_selection.h"
#include "vk/vk_check.h"

namespace aor {

VulkanError::VulkanError(VkResult r, const char* call, const char* file, int line)
    : std::runtime_error(fmt::format("Vulkan call failed with {}: {} ({}:{})", vkResultName(r), call, file, line)),
      result(r) {}

const char* vkResultName(VkResult result) {
  switch (result) {
    case VK_SUCCESS: return "VK_SUCCESS";
    case VK_NOT_READY: return "VK_NOT_READY";
    case VK_TIMEOUT: return "VK_TIMEOUT";
    case VK_ERROR_OUT_OF_HOST_MEMORY: return "VK_ERROR_OUT_OF_HOST_MEMORY";
    case VK_ERROR_OUT_OF_DEVICE_MEMORY: return "VK_ERROR_OUT_OF_DEVICE_MEMORY";
    case VK_ERROR_INITIALIZATION_FAILED: return "VK_ERROR_INITIALIZATION_FAILED";
    case VK_ERROR_DEVICE_LOST: return "VK_ERROR_DEVICE_LOST";
    case VK_ERROR_LAYER_NOT_PRESENT: return "VK_ERROR_LAYER_NOT_PRESENT";
    case VK_ERROR_EXTENSION_NOT_PRESENT: return "VK_ERROR_EXTENSION_NOT_PRESENT";
    case VK_ERROR_FEATURE_NOT_PRESENT: return "VK_ERROR_FEATURE_NOT_PRESENT";
    case VK_ERROR_INCOMPATIBLE_DRIVER: return "VK_ERROR_INCOMPATIBLE_DRIVER";
    default: return "VkResult error";
  }
}

size_t VulkanContext::validationMessageCount() {
  std::lock_guard lock(messageMutex);
  return validationMessages.size();
}

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

VKAPI_ATTR VkBool32 VKAPI_CALL onValidationMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                   VkDebugUtilsMessageTypeFlagsEXT,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  if (severity < VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) return VK_FALSE;
  auto* context = static_cast<VulkanContext*>(user);
  std::lock_guard lock(context->messageMutex);
  context->validationMessages.emplace_back(data->pMessage ? data->pMessage : "(no message)");
  fmt::print(stderr, "validation: {}\n", context->validationMessages.back());
  return VK_FALSE;
}

bool hasLayer(const char* name) {
  uint32_t count = 0;
  vkEnumerateInstanceLayerProperties(&count, nullptr);
  std::vector<VkLayerProperties> layers(count);
  vkEnumerateInstanceLayerProperties(&count, layers.data());
  return std::any_of(layers.begin(), layers.end(), [&](const auto& l) { return std::strcmp(l.layerName, name) == 0; });
}

VkInstance createInstance(bool validate) {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "aoreplay";
  app.apiVersion = VK_API_VERSION_1_3;

  std::vector<const char*> layers, extensions;
  VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
  VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = enables;
  if (validate) {
    if (!hasLayer(kValidationLayer))
      throw NoDeviceError("--validate needs the Khronos validation layer (Debian package vulkan-validationlayers)");
    layers.push_back(kValidationLayer);
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  }
  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pNext = validate ? &features : nullptr;
  info.pApplicationInfo = &app;
  info.enabledLayerCount = uint32_t(layers.size());
  info.ppEnabledLayerNames = layers.data();
  info.enabledExtensionCount = uint32_t(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  VkInstance instance = VK_NULL_HANDLE;
  VkResult result = vkCreateInstance(&info, nullptr, &instance);
  if (result == VK_ERROR_INCOMPATIBLE_DRIVER || result == VK_ERROR_INITIALIZATION_FAILED)
    throw NoDeviceError(fmt::format("no Vulkan driver found ({})", vkResultName(result)));
  VK_CHECK(result);
  return instance;
}

DeviceInfo describeDevice(VkPhysicalDevice device, uint32_t index) {
  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &driver};
  vkGetPhysicalDeviceProperties2(device, &props);
  DeviceInfo info;
  info.index = index;
  info.name = props.properties.deviceName;
  info.driver = driver.driverName;
  info.driverInfo = driver.driverInfo;
  info.apiVersion = fmt::format("{}.{}.{}", VK_API_VERSION_MAJOR(props.properties.apiVersion),
                                VK_API_VERSION_MINOR(props.properties.apiVersion),
                                VK_API_VERSION_PATCH(props.properties.apiVersion));
  info.isLavapipe = driver.driverID == VK_DRIVER_ID_MESA_LLVMPIPE;
  info.isCpu = props.properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
  uint32_t count = 0;
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr);
  std::vector<VkExtensionProperties> extensions(count);
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data());
  for (const auto& e : extensions) info.extensions.push_back(e.extensionName);
  info.limits = readDeviceLimits(device);
  return info;
}

std::vector<VkPhysicalDevice> physicalDevices(VkInstance instance) {
  uint32_t count = 0;
  vkEnumeratePhysicalDevices(instance, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  vkEnumeratePhysicalDevices(instance, &count, devices.data());
  return devices;
}

std::vector<DeviceInfo> describeDevices(const std::vector<VkPhysicalDevice>& devices) {
  std::vector<DeviceInfo> infos;
  for (uint32_t i = 0; i < devices.size(); ++i) infos.push_back(describeDevice(devices[i], i));
  return infos;
}

// Sets queueFamily to the first compute queue family that also has timestamps, and
// timestampValidBits to that family's.
void selectQueueFamily(VulkanContext& ctx) {
  uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(ctx.physicalDevice, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(ctx.physicalDevice, &count, families.data());
  for (uint32_t i = 0; i < count; ++i)
    if ((families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) && families[i].timestampValidBits > 0) {
      ctx.queueFamily = i;
      ctx.timestampValidBits = families[i].timestampValidBits;
      return;
    }
  throw NoDeviceError("the selected device has no compute queue with timestamp support");
}

// The ray-query group: ray queries need acceleration structures, which need deferred host operations
// and buffer device addresses. Enabled together or not at all.
const std::vector<std::string> kRayQueryGroup = {kRayQueryExtension, kAccelerationStructureExtension,
                                                 VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME};

// Whether the device offers the ray-query group's extensions and the features they need.
bool rayQueryGroupSupported(const VulkanContext& ctx) {
  for (const auto& e : kRayQueryGroup)
    if (!ctx.info.hasExtension(e)) return false;
  VkPhysicalDeviceRayQueryFeaturesKHR rayQuery{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR};
  VkPhysicalDeviceAccelerationStructureFeaturesKHR accel{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR, &rayQuery};
  VkPhysicalDeviceVulkan12Features features12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &accel};
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &features12};
  vkGetPhysicalDeviceFeatures2(ctx.physicalDevice, &features);
  return rayQuery.rayQuery && accel.accelerationStructure && features12.bufferDeviceAddress;
}

// The optional extensions to enable: those a run asks for that the device supports. Only the
// ray-query group is known; asking for anything else is a programming error.
std::vector<std::string> optionalExtensionsToEnable(const VulkanContext& ctx, const ContextOptions& options) {
  if (!options.optionalExtensions) return {};
  bool rayQuery = false;
  for (const auto& e : options.optionalExtensions(ctx.info)) {
    if (e != kRayQueryExtension && e != kAccelerationStructureExtension)
      throw std::logic_error(fmt::format("the Vulkan context cannot enable the optional extension {}", e));
    rayQuery = true;
  }
  return rayQuery && rayQueryGroupSupported(ctx) ? kRayQueryGroup : std::vector<std::string>{};
}

void createDevice(VulkanContext& ctx, const ContextOptions& options) {
  selectQueueFamily(ctx);
  float priority = 1.0f;
  VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queueInfo.queueFamilyIndex = ctx.queueFamily;
  queueInfo.queueCount = 1;
  queueInfo.pQueuePriorities = &priority;

  ctx.enabledOptionalExtensions = optionalExtensionsToEnable(ctx, options);
  bool rayQuery = ctx.enabled(kRayQueryExtension);
  VkPhysicalDeviceRayQueryFeaturesKHR rayQueryFeatures{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR};
  rayQueryFeatures.rayQuery = VK_TRUE;
  VkPhysicalDeviceAccelerationStructureFeaturesKHR accelFeatures{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR, &rayQueryFeatures};
  accelFeatures.accelerationStructure = VK_TRUE;
  VkPhysicalDeviceVulkan13Features features13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES,
                                              rayQuery ? &accelFeatures : nullptr};
  features13.synchronization2 = VK_TRUE;
  VkPhysicalDeviceVulkan12Features features12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &features13};
  features12.scalarBlockLayout = VK_TRUE;
  features12.bufferDeviceAddress = rayQuery ? VK_TRUE : VK_FALSE;  // acceleration structures are built from addresses
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &features12};
  features.features.shaderStorageImageWriteWithoutFormat = VK_TRUE;

  std::vector<const char*> extensions = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
  for (const auto& e : ctx.enabledOptionalExtensions) extensions.push_back(e.c_str());
  VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &features};
  info.queueCreateInfoCount = 1;
  info.pQueueCreateInfos = &queueInfo;
  info.enabledExtensionCount = uint32_t(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  VkResult result = vkCreateDevice(ctx.physicalDevice, &info, nullptr, &ctx.device);
  if (result == VK_ERROR_EXTENSION_NOT_PRESENT || result == VK_ERROR_FEATURE_NOT_PRESENT)
    throw NoDeviceError(fmt::format("device '{}' lacks Vulkan 1.3 with push descriptors, scalar block layout and synchronization2 ({})",
                                    ctx.info.name, vkResultName(result)));
  VK_CHECK(result);
  vkGetDeviceQueue(ctx.device, ctx.queueFamily, 0, &ctx.queue);
  ctx.cmdPushDescriptorSet =
      reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(vkGetDeviceProcAddr(ctx.device, "vkCmdPushDescriptorSetKHR"));
}

VkSampler createSampler(VkDevice device, VkFilter filter) {
  VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  info.magFilter = info.minFilter = filter;
  info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  info.maxLod = VK_LOD_CLAMP_NONE;  // textureLod reaches every level of a mip chain
  VkSampler sampler = VK_NULL_HANDLE;
  VK_CHECK(vkCreateSampler(device, &info, nullptr, &sampler));
  return sampler;
}

}  // namespace

bool DeviceInfo::hasExtension(const std::string& name) const {
  return std::find(extensions.begin(), extensions.end(), name) != extensions.end();
}

bool VulkanContext::enabled(const std::string& extension) const {
  return std::find(enabledOptionalExtensions.begin(), enabledOptionalExtensions.end(), extension) !=
         enabledOptionalExtensions.end();
}

std::string loaderVersion() {
  uint32_t version = VK_API_VERSION_1_0;  // a 1.0 loader lacks vkEnumerateInstanceVersion
  auto enumerate = reinterpret_cast<PFN_vkEnumerateInstanceVersion>(vkGetInstanceProcAddr(nullptr, "vkEnumerateInstanceVersion"));
  if (enumerate) enumerate(&version);
  return fmt::format("{}.{}.{}", VK_API_VERSION_MAJOR(version), VK_API_VERSION_MINOR(version), VK_API_VERSION_PATCH(version));
}

std::vector<DeviceInfo> listDevices() {
  VkInstance instance = createInstance(false);
  auto infos = describeDevices(physicalDevices(instance));
  vkDestroyInstance(instance, nullptr);
  return infos;
}

void createContext(VulkanContext& ctx, const ContextOptions& options) {
  ctx.instance = createInstance(options.validate);
  if (options.validate) {
    VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    info.pfnUserCallback = onValidationMessage;
    info.pUserData = &ctx;
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(ctx.instance, "vkCreateDebugUtilsMessengerEXT"));
    VK_CHECK(create(ctx.instance, &info, nullptr, &ctx.messenger));
  }
  auto devices = physicalDevices(ctx.instance);
  auto infos = describeDevices(devices);
  uint32_t chosen = selectDevice(infos, options.deviceSelector);
  ctx.physicalDevice = devices[chosen];
  ctx.info = infos[chosen];

  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(ctx.physicalDevice, &props);
  ctx.timestampPeriodNs = props.limits.timestampPeriod;
  vkGetPhysicalDeviceMemoryProperties(ctx.physicalDevice, &ctx.memoryProperties);
  createDevice(ctx, options);  // also picks the queue family and reads its timestampValidBits

  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  poolInfo.queueFamilyIndex = ctx.queueFamily;
  VK_CHECK(vkCreateCommandPool(ctx.device, &poolInfo, nullptr, &ctx.commandPool));
  ctx.nearestSampler = createSampler(ctx.device, VK_FILTER_NEAREST);
  ctx.linearSampler = createSampler(ctx.device, VK_FILTER_LINEAR);
}

void submitAndWait(const VulkanContext& ctx, VkCommandBuffer cmd, VkFence fence) {
  VkCommandBufferSubmitInfo cmdInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cmdInfo.commandBuffer = cmd;
  VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  submit.commandBufferInfoCount = 1;
  submit.pCommandBufferInfos = &cmdInfo;
  VK_CHECK(vkQueueSubmit2(ctx.queue, 1, &submit, fence));
  VK_CHECK(vkWaitForFences(ctx.device, 1, &fence, VK_TRUE, UINT64_MAX));
  // Counted cost: let a CPU device's queue thread finish what follows the fence's signal before
  // this thread goes on, so the two never race for the heap (their order moves the counts).
  if (ctx.settleAfterSubmit) {
    struct timespec settle{0, 2'000'000};
    nanosleep(&settle, nullptr);
  }
  VK_CHECK(vkResetFences(ctx.device, 1, &fence));
}

void runOneTimeCommands(const VulkanContext& ctx, const std::function<void(VkCommandBuffer)>& record) {
  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = ctx.commandPool;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VK_CHECK(vkAllocateCommandBuffers(ctx.device, &alloc, &cmd));
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
  record(cmd);
  VK_CHECK(vkEndCommandBuffer(cmd));
  VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence fence = VK_NULL_HANDLE;
  VK_CHECK(vkCreateFence(ctx.device, &fenceInfo, nullptr, &fence));
  submitAndWait(ctx, cmd, fence);
  vkDestroyFence(ctx.device, fence, nullptr);
  vkFreeCommandBuffers(ctx.device, ctx.commandPool, 1, &cmd);
}

double timestampDeltaMs(const VulkanContext& ctx, uint64_t from, uint64_t to) {
  uint64_t mask = ctx.timestampValidBits >= 64 ? ~0ull : ((1ull << ctx.timestampValidBits) - 1);
  return double((to - from) & mask) * ctx.timestampPeriodNs * 1e-6;
}

void destroyContext(VulkanContext& ctx) {
  if (ctx.device) {
    vkDeviceWaitIdle(ctx.device);
    vkDestroySampler(ctx.device, ctx.nearestSampler, nullptr);
    vkDestroySampler(ctx.device, ctx.linearSampler, nullptr);
    vkDestroyCommandPool(ctx.device, ctx.commandPool, nullptr);
    vkDestroyDevice(ctx.device, nullptr);
  }
  if (ctx.messenger) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(ctx.instance, "vkDestroyDebugUtilsMessengerEXT"));
    destroy(ctx.instance, ctx.messenger, nullptr);
  }
  if (ctx.instance) vkDestroyInstance(ctx.instance, nullptr);
  ctx.device = VK_NULL_HANDLE;
  ctx.enabledOptionalExtensions.clear();
  ctx.messenger = VK_NULL_HANDLE;
  ctx.instance = VK_NULL_HANDLE;
}

}  // namespace aor
