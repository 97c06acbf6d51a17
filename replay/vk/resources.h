#pragma once
// Plain structs for GPU images, buffers and compute pipelines, with free functions to make and
// destroy them. Owners (the replay's resource pool and the pass set) destroy in one place.
#include <cstdint>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>

namespace aor {

struct VulkanContext;

struct GpuImage {
  VkImage image = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;  // set only when the image owns its memory
  VkFormat format = VK_FORMAT_UNDEFINED;
  uint32_t width = 0, height = 0;
};

struct GpuBuffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  void* mapped = nullptr;  // host-visible buffers stay mapped
};

struct GpuMemory {
  VkDeviceMemory memory = VK_NULL_HANDLE;
};

uint32_t findMemoryType(const VulkanContext& ctx, uint32_t typeBits, VkMemoryPropertyFlags flags);

// Image without memory (bind it to own or shared memory afterwards).
GpuImage createImageUnbound(const VulkanContext& ctx, uint32_t width, uint32_t height, VkFormat format, VkImageUsageFlags usage);
void bindImage(const VulkanContext& ctx, GpuImage& image, VkDeviceMemory memory, VkDeviceSize offset);
// Image with its own device-local memory.
GpuImage createImage(const VulkanContext& ctx, uint32_t width, uint32_t height, VkFormat format, VkImageUsageFlags usage);
void destroyImage(const VulkanContext& ctx, GpuImage& image);

GpuMemory allocateDeviceMemory(const VulkanContext& ctx, VkDeviceSize size, uint32_t typeBits,
                               VkMemoryPropertyFlags flags = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
void freeMemory(const VulkanContext& ctx, GpuMemory& memory);

// Host-visible, host-coherent, persistently mapped buffer for uploads and read-backs.
GpuBuffer createHostBuffer(const VulkanContext& ctx, VkDeviceSize size, VkBufferUsageFlags usage);
void destroyBuffer(const VulkanContext& ctx, GpuBuffer& buffer);

struct ComputePipeline {
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;  // push-descriptor set 0
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkPipeline pipeline = VK_NULL_HANDLE;
  uint32_t pushConstantSize = 0;
  uint32_t workgroupSize = 0;  // the shader's square workgroup, in pixels a side
  std::vector<VkDescriptorType> bindings;  // type of set 0's binding i
};

struct SpecializationValue {
  uint32_t id;
  uint32_t value;  // ints and bools (VkBool32) alike
};

ComputePipeline createComputePipeline(const VulkanContext& ctx, std::span<const uint32_t> spirv,
                                      std::span<const VkDescriptorType> bindings, uint32_t pushConstantSize,
                                      std::span<const SpecializationValue> specialization);
void destroyPipeline(const VulkanContext& ctx, ComputePipeline& pipeline);

}  // namespace aor
