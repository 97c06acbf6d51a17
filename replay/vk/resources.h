#pragma once
// Plain structs for GPU images, buffers and compute pipelines, with free functions to make and
// destroy them. Owners (the graph's physical resources, the pipeline cache) destroy in one place.
#include <cstdint>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>

#include "vk/shader_reflection.h"

namespace aor {

struct VulkanContext;

// A view of some mip levels and layers of an image, as a 2D or a 2D-array view.
struct ImageViewKey {
  uint32_t baseMip = 0, mipCount = 1, baseLayer = 0, layerCount = 1;
  bool arrayed = false;
  bool operator==(const ImageViewKey&) const = default;
};

struct GpuImage {
  VkImage image = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;       // every level and layer (2D-array view when layers > 1)
  VkDeviceMemory memory = VK_NULL_HANDLE;  // set only when the image owns its memory
  VkFormat format = VK_FORMAT_UNDEFINED;
  uint32_t width = 0, height = 0, mipLevels = 1, arrayLayers = 1;
  // Views of parts of the image, made when a dispatch first binds them; destroyed with the image.
  mutable std::vector<std::pair<ImageViewKey, VkImageView>> partViews;
};

struct GpuBuffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;  // set only when the buffer owns its memory
  void* mapped = nullptr;                  // host-visible buffers stay mapped
  VkDeviceSize size = 0;
  // Set when the buffer holds an acceleration structure a shader binds (its owner made both).
  VkAccelerationStructureKHR accelerationStructure = VK_NULL_HANDLE;
};

struct GpuMemory {
  VkDeviceMemory memory = VK_NULL_HANDLE;
};

uint32_t findMemoryType(const VulkanContext& ctx, uint32_t typeBits, VkMemoryPropertyFlags flags);

struct ImageShape {
  uint32_t width = 0, height = 0;
  VkFormat format = VK_FORMAT_UNDEFINED;
  uint32_t mipLevels = 1, arrayLayers = 1;
};
// Image without memory (bind it to own or shared memory afterwards).
GpuImage createImageUnbound(const VulkanContext& ctx, const ImageShape& shape, VkImageUsageFlags usage);
void bindImage(const VulkanContext& ctx, GpuImage& image, VkDeviceMemory memory, VkDeviceSize offset);
// Image with its own device-local memory.
GpuImage createImage(const VulkanContext& ctx, const ImageShape& shape, VkImageUsageFlags usage);
inline GpuImage createImage(const VulkanContext& ctx, uint32_t width, uint32_t height, VkFormat format,
                            VkImageUsageFlags usage) {
  return createImage(ctx, ImageShape{width, height, format}, usage);
}
// The view of `key`'s levels and layers (the image's own view when it covers the whole image the
// same way), made on first use.
VkImageView imageViewOf(const VulkanContext& ctx, const GpuImage& image, const ImageViewKey& key);
void destroyImage(const VulkanContext& ctx, GpuImage& image);

GpuMemory allocateDeviceMemory(const VulkanContext& ctx, VkDeviceSize size, uint32_t typeBits,
                               VkMemoryPropertyFlags flags = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
void freeMemory(const VulkanContext& ctx, GpuMemory& memory);

// Host-visible, host-coherent, persistently mapped buffer for uploads and read-backs.
GpuBuffer createHostBuffer(const VulkanContext& ctx, VkDeviceSize size, VkBufferUsageFlags usage);
// Device-local buffer without memory (for the graph's transients, which share memory), and with
// its own memory.
GpuBuffer createBufferUnbound(const VulkanContext& ctx, VkDeviceSize size, VkBufferUsageFlags usage);
void bindBuffer(const VulkanContext& ctx, GpuBuffer& buffer, VkDeviceMemory memory, VkDeviceSize offset);
GpuBuffer createDeviceBuffer(const VulkanContext& ctx, VkDeviceSize size, VkBufferUsageFlags usage);
void destroyBuffer(const VulkanContext& ctx, GpuBuffer& buffer);

struct ComputePipeline {
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;  // push-descriptor set 0
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkPipeline pipeline = VK_NULL_HANDLE;
  ShaderInterface shader;     // reflected from the SPIR-V: bindings, push constants
  uint32_t localSize[3] = {1, 1, 1};  // the workgroup size, specialisation constants applied
};

struct SpecializationValue {
  uint32_t id;
  uint32_t value;  // ints and bools (VkBool32) alike
};
// A shader header's constant id with an int or bool value (true is 1, as VkBool32).
inline SpecializationValue specializationValue(int64_t id, int64_t value) { return {uint32_t(id), uint32_t(value)}; }

// Bindings, push-constant size and workgroup size come from the SPIR-V (vk/shader_reflection.h);
// `name` names the shader in errors.
ComputePipeline createComputePipeline(const VulkanContext& ctx, std::span<const uint32_t> spirv, const std::string& name,
                                      std::span<const SpecializationValue> specialization = {});
void destroyPipeline(const VulkanContext& ctx, ComputePipeline& pipeline);

}  // namespace aor
