#include "vk/resources.h"

#include <optional>

#include <fmt/format.h>

#include "vk/context.h"
#include "vk/vk_check.h"

namespace aor {
namespace {

std::optional<uint32_t> matchingMemoryType(const VulkanContext& ctx, uint32_t typeBits, VkMemoryPropertyFlags flags) {
  const auto& props = ctx.memoryProperties;
  for (uint32_t i = 0; i < props.memoryTypeCount; ++i)
    if ((typeBits & (1u << i)) && (props.memoryTypes[i].propertyFlags & flags) == flags) return i;
  return std::nullopt;
}

bool hasMemoryType(const VulkanContext& ctx, uint32_t typeBits, VkMemoryPropertyFlags flags) {
  return matchingMemoryType(ctx, typeBits, flags).has_value();
}

}  // namespace

uint32_t findMemoryType(const VulkanContext& ctx, uint32_t typeBits, VkMemoryPropertyFlags flags) {
  if (auto type = matchingMemoryType(ctx, typeBits, flags)) return *type;
  throw std::runtime_error(fmt::format("no Vulkan memory type with flags {:#x} among bits {:#x}", flags, typeBits));
}

GpuImage createImageUnbound(const VulkanContext& ctx, const ImageShape& shape, VkImageUsageFlags usage) {
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = shape.format;
  info.extent = {shape.width, shape.height, 1};
  info.mipLevels = shape.mipLevels;
  info.arrayLayers = shape.arrayLayers;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = usage;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  GpuImage image;
  image.format = shape.format;
  image.width = shape.width;
  image.height = shape.height;
  image.mipLevels = shape.mipLevels;
  image.arrayLayers = shape.arrayLayers;
  VK_CHECK(vkCreateImage(ctx.device, &info, nullptr, &image.image));
  return image;
}

namespace {

VkImageView createView(const VulkanContext& ctx, const GpuImage& image, const ImageViewKey& key) {
  VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  view.image = image.image;
  view.viewType = key.arrayed ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D;
  view.format = image.format;
  view.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, key.baseMip, key.mipCount, key.baseLayer, key.layerCount};
  VkImageView handle = VK_NULL_HANDLE;
  VK_CHECK(vkCreateImageView(ctx.device, &view, nullptr, &handle));
  return handle;
}

ImageViewKey wholeImage(const GpuImage& image) {
  return {0, image.mipLevels, 0, image.arrayLayers, image.arrayLayers > 1};
}

}  // namespace

void bindImage(const VulkanContext& ctx, GpuImage& image, VkDeviceMemory memory, VkDeviceSize offset) {
  VK_CHECK(vkBindImageMemory(ctx.device, image.image, memory, offset));
  image.view = createView(ctx, image, wholeImage(image));
}

GpuImage createImage(const VulkanContext& ctx, const ImageShape& shape, VkImageUsageFlags usage) {
  GpuImage image = createImageUnbound(ctx, shape, usage);
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(ctx.device, image.image, &req);
  GpuMemory memory = allocateDeviceMemory(ctx, req.size, req.memoryTypeBits);
  image.memory = memory.memory;
  bindImage(ctx, image, image.memory, 0);
  return image;
}

VkImageView imageViewOf(const VulkanContext& ctx, const GpuImage& image, const ImageViewKey& key) {
  if (key == wholeImage(image)) return image.view;
  for (const auto& [k, view] : image.partViews)
    if (k == key) return view;
  image.partViews.emplace_back(key, createView(ctx, image, key));
  return image.partViews.back().second;
}

void destroyImage(const VulkanContext& ctx, GpuImage& image) {
  for (auto& [key, view] : image.partViews) vkDestroyImageView(ctx.device, view, nullptr);
  if (image.view) vkDestroyImageView(ctx.device, image.view, nullptr);
  if (image.image) vkDestroyImage(ctx.device, image.image, nullptr);
  if (image.memory) vkFreeMemory(ctx.device, image.memory, nullptr);
  image = {};
}

GpuMemory allocateDeviceMemory(const VulkanContext& ctx, VkDeviceSize size, uint32_t typeBits, VkMemoryPropertyFlags flags) {
  VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  info.allocationSize = size;
  info.memoryTypeIndex = findMemoryType(ctx, typeBits, flags);
  GpuMemory memory;
  VK_CHECK(vkAllocateMemory(ctx.device, &info, nullptr, &memory.memory));
  return memory;
}

void freeMemory(const VulkanContext& ctx, GpuMemory& memory) {
  if (memory.memory) vkFreeMemory(ctx.device, memory.memory, nullptr);
  memory = {};
}

GpuBuffer createBufferUnbound(const VulkanContext& ctx, VkDeviceSize size, VkBufferUsageFlags usage) {
  GpuBuffer buffer;
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size;
  info.usage = usage;
  VK_CHECK(vkCreateBuffer(ctx.device, &info, nullptr, &buffer.buffer));
  buffer.size = size;
  return buffer;
}

void bindBuffer(const VulkanContext& ctx, GpuBuffer& buffer, VkDeviceMemory memory, VkDeviceSize offset) {
  VK_CHECK(vkBindBufferMemory(ctx.device, buffer.buffer, memory, offset));
}

GpuBuffer createDeviceBuffer(const VulkanContext& ctx, VkDeviceSize size, VkBufferUsageFlags usage) {
  GpuBuffer buffer = createBufferUnbound(ctx, size, usage);
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(ctx.device, buffer.buffer, &req);
  buffer.memory = allocateDeviceMemory(ctx, req.size, req.memoryTypeBits).memory;
  bindBuffer(ctx, buffer, buffer.memory, 0);
  return buffer;
}

GpuBuffer createHostBuffer(const VulkanContext& ctx, VkDeviceSize size, VkBufferUsageFlags usage) {
  GpuBuffer buffer = createBufferUnbound(ctx, size, usage);
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(ctx.device, buffer.buffer, &req);
  VkMemoryPropertyFlags flags = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  // The host reads what the GPU writes into a read-back buffer: uncached (write-combined) memory
  // makes those reads slow on discrete GPUs, so cached memory is preferred where there is some.
  if ((usage & VK_BUFFER_USAGE_TRANSFER_DST_BIT) && hasMemoryType(ctx, req.memoryTypeBits, flags | VK_MEMORY_PROPERTY_HOST_CACHED_BIT))
    flags |= VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
  buffer.memory = allocateDeviceMemory(ctx, req.size, req.memoryTypeBits, flags).memory;
  bindBuffer(ctx, buffer, buffer.memory, 0);
  VK_CHECK(vkMapMemory(ctx.device, buffer.memory, 0, VK_WHOLE_SIZE, 0, &buffer.mapped));
  return buffer;
}

void destroyBuffer(const VulkanContext& ctx, GpuBuffer& buffer) {
  if (buffer.buffer) vkDestroyBuffer(ctx.device, buffer.buffer, nullptr);
  if (buffer.memory) vkFreeMemory(ctx.device, buffer.memory, nullptr);
  buffer = {};
}

ComputePipeline createComputePipeline(const VulkanContext& ctx, std::span<const uint32_t> spirv, const std::string& name,
                                      std::span<const SpecializationValue> specialization) {
  ComputePipeline p;
  p.shader = reflectComputeShader(spirv, name);
  for (int d = 0; d < 3; ++d) {
    p.localSize[d] = p.shader.localSize[d];
    for (const auto& s : specialization)
      if (p.shader.localSizeSpecId[d] >= 0 && s.id == uint32_t(p.shader.localSizeSpecId[d])) p.localSize[d] = s.value;
  }
  if (auto exceeded = exceededLimit(p.shader, {p.localSize[0], p.localSize[1], p.localSize[2]}, ctx.info.limits))
    throw std::runtime_error(fmt::format("shader {} needs {} on device '{}'", name, *exceeded, ctx.info.name));
  std::vector<VkDescriptorSetLayoutBinding> layoutBindings;
  for (uint32_t i = 0; i < p.shader.bindings.size(); ++i)
    layoutBindings.push_back({i, p.shader.bindings[i].type, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
  if (p.shader.opCounterBinding >= 0)
    layoutBindings.push_back({uint32_t(p.shader.opCounterBinding), VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
  VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  setInfo.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
  setInfo.bindingCount = uint32_t(layoutBindings.size());
  setInfo.pBindings = layoutBindings.data();
  VK_CHECK(vkCreateDescriptorSetLayout(ctx.device, &setInfo, nullptr, &p.setLayout));

  uint32_t pushConstantSize = p.shader.pushConstantBytes;
  VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, pushConstantSize};
  VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layoutInfo.setLayoutCount = 1;
  layoutInfo.pSetLayouts = &p.setLayout;
  layoutInfo.pushConstantRangeCount = pushConstantSize ? 1 : 0;
  layoutInfo.pPushConstantRanges = &range;
  VK_CHECK(vkCreatePipelineLayout(ctx.device, &layoutInfo, nullptr, &p.layout));

  VkShaderModuleCreateInfo moduleInfo{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  moduleInfo.codeSize = spirv.size_bytes();
  moduleInfo.pCode = spirv.data();
  VkShaderModule module = VK_NULL_HANDLE;
  VK_CHECK(vkCreateShaderModule(ctx.device, &moduleInfo, nullptr, &module));

  std::vector<VkSpecializationMapEntry> entries;
  std::vector<uint32_t> values;
  for (const auto& s : specialization) {
    entries.push_back({s.id, uint32_t(values.size() * sizeof(uint32_t)), sizeof(uint32_t)});
    values.push_back(s.value);
  }
  VkSpecializationInfo specInfo{uint32_t(entries.size()), entries.data(), values.size() * sizeof(uint32_t), values.data()};
  VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = module;
  info.stage.pName = "main";
  info.stage.pSpecializationInfo = entries.empty() ? nullptr : &specInfo;
  info.layout = p.layout;
  VkResult result = vkCreateComputePipelines(ctx.device, VK_NULL_HANDLE, 1, &info, nullptr, &p.pipeline);
  vkDestroyShaderModule(ctx.device, module, nullptr);
  VK_CHECK(result);
  return p;
}

void destroyPipeline(const VulkanContext& ctx, ComputePipeline& p) {
  if (p.pipeline) vkDestroyPipeline(ctx.device, p.pipeline, nullptr);
  if (p.layout) vkDestroyPipelineLayout(ctx.device, p.layout, nullptr);
  if (p.setLayout) vkDestroyDescriptorSetLayout(ctx.device, p.setLayout, nullptr);
  p = {};
}

}  // namespace aor
