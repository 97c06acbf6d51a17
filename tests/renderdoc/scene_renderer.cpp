#include "scene_renderer.h"

#include <cstdio>
#include <cstring>
#include <stdexcept>

#include <glm/gtc/type_ptr.hpp>

#include "rd_scene_spirv.h"

namespace aor::rdtest {
namespace {

// scene.vert's Object block: view and projection, the 128 bytes every device allows.
constexpr uint32_t kPushBytes = 128;


void check(VkResult r, const char* what) {
  if (r != VK_SUCCESS) throw std::runtime_error(std::string(what) + " failed: VkResult " + std::to_string(int(r)));
}

bool hasStencil(VkFormat f) { return f == VK_FORMAT_D24_UNORM_S8_UINT || f == VK_FORMAT_D32_SFLOAT_S8_UINT; }

VKAPI_ATTR VkBool32 VKAPI_CALL countMessage(VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
                                            const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  std::fprintf(stderr, "validation: %s\n", data->pMessage);
  ++*static_cast<size_t*>(user);
  return VK_FALSE;
}

bool instanceHasExtension(const char* name) {
  uint32_t n = 0;
  vkEnumerateInstanceExtensionProperties(nullptr, &n, nullptr);
  std::vector<VkExtensionProperties> all(n);
  vkEnumerateInstanceExtensionProperties(nullptr, &n, all.data());
  for (const auto& e : all)
    if (std::strcmp(e.extensionName, name) == 0) return true;
  return false;
}

}  // namespace

struct Image {
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
};

struct Buffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  void* mapped = nullptr;
};

struct SceneRenderer::State {
  RenderOptions o;
  SceneMesh mesh = sceneMesh();
  size_t validationMessages = 0;
  bool debugUtils = false;
  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  uint32_t family = 0;
  VkQueue queue = VK_NULL_HANDLE;
  Image depth, normals, overlay;
  Image depthResolved, normalsResolved;  // multisampled G-buffer: sample 0 of depth, normals averaged
  const Image& readDepth() const { return o.samples > 1 ? depthResolved : depth; }
  const Image& readNormals() const { return o.samples > 1 ? normalsResolved : normals; }
  VkRenderPass gbufferPass = VK_NULL_HANDLE, overlayPass = VK_NULL_HANDLE;
  VkFramebuffer gbufferFramebuffer = VK_NULL_HANDLE, overlayFramebuffer = VK_NULL_HANDLE;
  Buffer uniforms, extra, vertices, depthReadback, normalReadback;
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  VkDescriptorSet set = VK_NULL_HANDLE;
  VkPipelineLayout pipelineLayout = VK_NULL_HANDLE;
  VkPipeline gbufferPipeline = VK_NULL_HANDLE, overlayPipeline = VK_NULL_HANDLE, compositePipeline = VK_NULL_HANDLE;
  VkCommandPool commandPool = VK_NULL_HANDLE;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;

  // Reversed depth, by the projection or by a viewport depth range from 1 to 0 (not both).
  bool farIsZero() const { return o.reversed != (o.minDepth > o.maxDepth); }
  void createInstance();
  void createDevice();
  uint32_t memoryType(uint32_t bits, VkMemoryPropertyFlags flags) const;
  Image createImage(VkFormat format, VkImageUsageFlags usage, VkImageAspectFlags aspect, const char* name,
                    int samples = 1);
  Buffer createBuffer(VkDeviceSize size, VkBufferUsageFlags usage);
  void name(VkObjectType type, uint64_t handle, const char* label);
  VkRenderPass createRenderPass(bool withDepth);
  VkFramebuffer createFramebuffer(VkRenderPass pass, std::vector<VkImageView> views);
  void createDescriptors();
  VkPipeline createPipeline(VkRenderPass pass, bool withDepth, bool composite = false);
  void record(const Camera& camera);
  void label(const char* text, bool begin);
  void destroy();
};

void SceneRenderer::State::createInstance() {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "rd_scene";
  app.apiVersion = VK_API_VERSION_1_2;
  std::vector<const char*> extensions, layers;
  debugUtils = instanceHasExtension(VK_EXT_DEBUG_UTILS_EXTENSION_NAME) || o.validate;
  if (debugUtils) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  if (o.validate) layers.push_back("VK_LAYER_KHRONOS_validation");
  VkValidationFeatureEnableEXT sync = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
  VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = &sync;
  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pNext = o.validate ? &features : nullptr;
  info.pApplicationInfo = &app;
  info.enabledExtensionCount = uint32_t(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  info.enabledLayerCount = uint32_t(layers.size());
  info.ppEnabledLayerNames = layers.data();
  check(vkCreateInstance(&info, nullptr, &instance), "vkCreateInstance");
  if (!o.validate) return;
  VkDebugUtilsMessengerCreateInfoEXT m{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  m.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  m.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                  VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  m.pfnUserCallback = countMessage;
  m.pUserData = &validationMessages;
  auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
      vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
  check(create(instance, &m, nullptr, &messenger), "vkCreateDebugUtilsMessengerEXT");
}

void SceneRenderer::State::createDevice() {
  uint32_t n = 0;
  vkEnumeratePhysicalDevices(instance, &n, nullptr);
  if (n == 0) throw std::runtime_error("no Vulkan device");
  std::vector<VkPhysicalDevice> devices(n);
  vkEnumeratePhysicalDevices(instance, &n, devices.data());
  physical = devices[0];
  for (VkPhysicalDevice d : devices) {  // lavapipe, as the rest of the project, when present
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(d, &p);
    if (std::strstr(p.deviceName, "llvmpipe")) physical = d;
  }
  uint32_t families = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physical, &families, nullptr);
  std::vector<VkQueueFamilyProperties> props(families);
  vkGetPhysicalDeviceQueueFamilyProperties(physical, &families, props.data());
  while (family < families && !(props[family].queueFlags & VK_QUEUE_GRAPHICS_BIT)) ++family;
  if (family == families) throw std::runtime_error("no graphics queue");
  float priority = 1.0f;
  VkDeviceQueueCreateInfo q{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  q.queueFamilyIndex = family;
  q.queueCount = 1;
  q.pQueuePriorities = &priority;
  VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  info.queueCreateInfoCount = 1;
  info.pQueueCreateInfos = &q;
  check(vkCreateDevice(physical, &info, nullptr, &device), "vkCreateDevice");
  vkGetDeviceQueue(device, family, 0, &queue);
}

uint32_t SceneRenderer::State::memoryType(uint32_t bits, VkMemoryPropertyFlags flags) const {
  VkPhysicalDeviceMemoryProperties mp;
  vkGetPhysicalDeviceMemoryProperties(physical, &mp);
  for (uint32_t i = 0; i < mp.memoryTypeCount; ++i)
    if ((bits & (1u << i)) && (mp.memoryTypes[i].propertyFlags & flags) == flags) return i;
  throw std::runtime_error("no suitable memory type");
}

void SceneRenderer::State::name(VkObjectType type, uint64_t handle, const char* label) {
  if (!debugUtils) return;
  auto setName = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
      vkGetInstanceProcAddr(instance, "vkSetDebugUtilsObjectNameEXT"));
  VkDebugUtilsObjectNameInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
  info.objectType = type;
  info.objectHandle = handle;
  info.pObjectName = label;
  setName(device, &info);
}

Image SceneRenderer::State::createImage(VkFormat format, VkImageUsageFlags usage, VkImageAspectFlags aspect,
                                        const char* label, int samples) {
  Image img;
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = format;
  info.extent = {uint32_t(o.width), uint32_t(o.height), 1};
  info.mipLevels = 1;
  info.arrayLayers = 1;
  info.samples = VkSampleCountFlagBits(samples);
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = usage;
  check(vkCreateImage(device, &info, nullptr, &img.image), "vkCreateImage");
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(device, img.image, &req);
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = req.size;
  alloc.memoryTypeIndex = memoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  check(vkAllocateMemory(device, &alloc, nullptr, &img.memory), "vkAllocateMemory");
  check(vkBindImageMemory(device, img.image, img.memory, 0), "vkBindImageMemory");
  VkImageViewCreateInfo v{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  v.image = img.image;
  v.viewType = VK_IMAGE_VIEW_TYPE_2D;
  v.format = format;
  v.subresourceRange = {aspect, 0, 1, 0, 1};
  check(vkCreateImageView(device, &v, nullptr, &img.view), "vkCreateImageView");
  name(VK_OBJECT_TYPE_IMAGE, uint64_t(img.image), label);
  return img;
}

Buffer SceneRenderer::State::createBuffer(VkDeviceSize size, VkBufferUsageFlags usage) {
  Buffer b;
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size;
  info.usage = usage;
  check(vkCreateBuffer(device, &info, nullptr, &b.buffer), "vkCreateBuffer");
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(device, b.buffer, &req);
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = req.size;
  alloc.memoryTypeIndex =
      memoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  check(vkAllocateMemory(device, &alloc, nullptr, &b.memory), "vkAllocateMemory");
  check(vkBindBufferMemory(device, b.buffer, b.memory, 0), "vkBindBufferMemory");
  check(vkMapMemory(device, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped), "vkMapMemory");
  return b;
}

// Both passes end with their images ready for the copies; the incoming dependency orders this
// frame's attachment writes after the previous frame's copies and writes. A multisampled G-buffer
// resolves into single-sample images (depth: sample 0; normals: the average), which are copied.
VkRenderPass SceneRenderer::State::createRenderPass(bool withDepth) {
  const bool multisampled = withDepth && o.samples > 1;
  const VkSampleCountFlagBits samples = multisampled ? VkSampleCountFlagBits(o.samples) : VK_SAMPLE_COUNT_1_BIT;
  auto attachment = [&](VkFormat format, VkSampleCountFlagBits count, VkImageLayout finalLayout) {
    VkAttachmentDescription2 a{VK_STRUCTURE_TYPE_ATTACHMENT_DESCRIPTION_2};
    a.format = format;
    a.samples = count;
    a.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    a.stencilLoadOp = hasStencil(format) ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    a.stencilStoreOp = hasStencil(format) ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_DONT_CARE;
    a.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    a.finalLayout = finalLayout;
    return a;
  };
  const VkImageLayout copied = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  const VkImageLayout kept = multisampled ? VK_IMAGE_LAYOUT_GENERAL : copied;  // the copies read the resolved images
  std::vector<VkAttachmentDescription2> attachments;
  if (!withDepth) {
    attachments.push_back(attachment(VK_FORMAT_R8G8B8A8_UNORM, samples, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL));
  } else {
    attachments.push_back(attachment(VK_FORMAT_R16G16B16A16_SFLOAT, samples, kept));
    attachments.push_back(attachment(o.depthFormat, samples, kept));
    if (multisampled) {
      attachments.push_back(attachment(VK_FORMAT_R16G16B16A16_SFLOAT, VK_SAMPLE_COUNT_1_BIT, copied));
      attachments.push_back(attachment(o.depthFormat, VK_SAMPLE_COUNT_1_BIT, copied));
      attachments[2].loadOp = attachments[3].loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
      attachments[3].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    }
  }
  const VkImageAspectFlags depthAspects = VK_IMAGE_ASPECT_DEPTH_BIT | (hasStencil(o.depthFormat) ? VK_IMAGE_ASPECT_STENCIL_BIT : 0);
  const VkAttachmentReference2 color{VK_STRUCTURE_TYPE_ATTACHMENT_REFERENCE_2, nullptr, 0,
                                     VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_ASPECT_COLOR_BIT};
  const VkAttachmentReference2 depthRef{VK_STRUCTURE_TYPE_ATTACHMENT_REFERENCE_2, nullptr, 1,
                                        VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL, depthAspects};
  const VkAttachmentReference2 colorResolve{VK_STRUCTURE_TYPE_ATTACHMENT_REFERENCE_2, nullptr, 2,
                                            VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_ASPECT_COLOR_BIT};
  const VkAttachmentReference2 depthResolve{VK_STRUCTURE_TYPE_ATTACHMENT_REFERENCE_2, nullptr, 3,
                                            VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL, depthAspects};
  VkSubpassDescriptionDepthStencilResolve resolve{VK_STRUCTURE_TYPE_SUBPASS_DESCRIPTION_DEPTH_STENCIL_RESOLVE};
  resolve.depthResolveMode = VK_RESOLVE_MODE_SAMPLE_ZERO_BIT;
  resolve.stencilResolveMode = hasStencil(o.depthFormat) ? VK_RESOLVE_MODE_SAMPLE_ZERO_BIT : VK_RESOLVE_MODE_NONE;
  resolve.pDepthStencilResolveAttachment = &depthResolve;
  VkSubpassDescription2 subpass{VK_STRUCTURE_TYPE_SUBPASS_DESCRIPTION_2, multisampled ? &resolve : nullptr};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &color;
  subpass.pResolveAttachments = multisampled ? &colorResolve : nullptr;
  subpass.pDepthStencilAttachment = withDepth ? &depthRef : nullptr;
  const VkPipelineStageFlags attachmentStages = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                                                VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                                                VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  const VkAccessFlags attachmentWrites =
      VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  const VkAccessFlags attachmentAccess = attachmentWrites | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT;
  VkSubpassDependency2 deps[2] = {{VK_STRUCTURE_TYPE_SUBPASS_DEPENDENCY_2}, {VK_STRUCTURE_TYPE_SUBPASS_DEPENDENCY_2}};
  deps[0].srcSubpass = VK_SUBPASS_EXTERNAL;
  deps[0].dstSubpass = 0;
  deps[0].srcStageMask = attachmentStages | VK_PIPELINE_STAGE_TRANSFER_BIT;
  deps[0].srcAccessMask = attachmentWrites;
  deps[0].dstStageMask = attachmentStages;
  deps[0].dstAccessMask = attachmentAccess;
  deps[1].srcSubpass = 0;
  deps[1].dstSubpass = VK_SUBPASS_EXTERNAL;
  deps[1].srcStageMask = attachmentStages;
  deps[1].srcAccessMask = attachmentWrites;
  deps[1].dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
  deps[1].dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
  VkRenderPassCreateInfo2 info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO_2};
  info.attachmentCount = uint32_t(attachments.size());
  info.pAttachments = attachments.data();
  info.subpassCount = 1;
  info.pSubpasses = &subpass;
  info.dependencyCount = 2;
  info.pDependencies = deps;
  VkRenderPass pass;
  check(vkCreateRenderPass2(device, &info, nullptr, &pass), "vkCreateRenderPass2");
  return pass;
}

VkFramebuffer SceneRenderer::State::createFramebuffer(VkRenderPass pass, std::vector<VkImageView> views) {
  VkFramebufferCreateInfo info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
  info.renderPass = pass;
  info.attachmentCount = uint32_t(views.size());
  info.pAttachments = views.data();
  info.width = uint32_t(o.width);
  info.height = uint32_t(o.height);
  info.layers = 1;
  VkFramebuffer fb;
  check(vkCreateFramebuffer(device, &info, nullptr, &fb), "vkCreateFramebuffer");
  return fb;
}

void SceneRenderer::State::createDescriptors() {
  const VkDescriptorSetLayoutBinding bindings[2] = {
      {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_VERTEX_BIT, nullptr},
      {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_VERTEX_BIT, nullptr}};
  VkDescriptorSetLayoutCreateInfo layout{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  layout.bindingCount = 2;
  layout.pBindings = bindings;
  check(vkCreateDescriptorSetLayout(device, &layout, nullptr, &setLayout), "vkCreateDescriptorSetLayout");
  const VkDescriptorPoolSize sizes[2] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1}, {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1}};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.maxSets = 1;
  poolInfo.poolSizeCount = 2;
  poolInfo.pPoolSizes = sizes;
  check(vkCreateDescriptorPool(device, &poolInfo, nullptr, &pool), "vkCreateDescriptorPool");
  VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  alloc.descriptorPool = pool;
  alloc.descriptorSetCount = 1;
  alloc.pSetLayouts = &setLayout;
  check(vkAllocateDescriptorSets(device, &alloc, &set), "vkAllocateDescriptorSets");
  const VkDescriptorBufferInfo bufferInfos[2] = {{uniforms.buffer, 0, VK_WHOLE_SIZE}, {extra.buffer, 0, VK_WHOLE_SIZE}};
  VkWriteDescriptorSet writes[2] = {{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}, {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}};
  for (uint32_t i = 0; i < 2; ++i) {
    writes[i].dstSet = set;
    writes[i].dstBinding = i;
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = i == 0 ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[i].pBufferInfo = &bufferInfos[i];
  }
  vkUpdateDescriptorSets(device, 2, writes, 0, nullptr);
  const VkPushConstantRange model{VK_SHADER_STAGE_VERTEX_BIT, 0, kPushBytes};
  VkPipelineLayoutCreateInfo pl{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  pl.setLayoutCount = 1;
  pl.pSetLayouts = &setLayout;
  pl.pushConstantRangeCount = 1;
  pl.pPushConstantRanges = &model;
  check(vkCreatePipelineLayout(device, &pl, nullptr, &pipelineLayout), "vkCreatePipelineLayout");
}

// `composite`: in the depth pass with depth test, depth writes and colour writes off (a stand-in for
// a post-processing draw after the scene, which the import's default event must pass over).
VkPipeline SceneRenderer::State::createPipeline(VkRenderPass pass, bool withDepth, bool composite) {
  auto module = [&](const uint32_t* words, size_t count) {
    VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    info.codeSize = count * 4;
    info.pCode = words;
    VkShaderModule m;
    check(vkCreateShaderModule(device, &info, nullptr, &m), "vkCreateShaderModule");
    return m;
  };
  VkShaderModule vert = o.strippedNames ? module(spirv::scene_vert_stripped, spirv::scene_vert_stripped_words)
                                        : module(spirv::scene_vert, spirv::scene_vert_words);
  const int constants[2] = {o.cameraLayout, o.glDepthRow ? 1 : 0};
  const VkSpecializationMapEntry entries[2] = {{0, 0, sizeof(int)}, {1, sizeof(int), sizeof(VkBool32)}};
  const VkSpecializationInfo layoutConstant{2, entries, sizeof constants, constants};
  VkShaderModule frag = module(spirv::scene_frag, spirv::scene_frag_words);
  VkPipelineShaderStageCreateInfo stages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                               {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = vert;
  stages[0].pName = "main";
  stages[0].pSpecializationInfo = &layoutConstant;
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = frag;
  stages[1].pName = "main";
  VkVertexInputBindingDescription binding{0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX};
  VkVertexInputAttributeDescription attributes[2] = {
      {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)},
      {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, normal)}};
  VkPipelineVertexInputStateCreateInfo input{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  input.vertexBindingDescriptionCount = 1;
  input.pVertexBindingDescriptions = &binding;
  input.vertexAttributeDescriptionCount = 2;
  input.pVertexAttributeDescriptions = attributes;
  VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkViewport viewport{0, 0, float(o.width), float(o.height), o.minDepth, o.maxDepth};
  VkRect2D scissor{{0, 0}, {uint32_t(o.width), uint32_t(o.height)}};
  VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  vp.viewportCount = 1;
  vp.pViewports = &viewport;
  vp.scissorCount = 1;
  vp.pScissors = &scissor;
  VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = VK_CULL_MODE_NONE;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  ms.rasterizationSamples = withDepth ? VkSampleCountFlagBits(o.samples) : VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  ds.depthTestEnable = withDepth && !composite;
  ds.depthWriteEnable = withDepth && !composite;
  ds.depthCompareOp = farIsZero() ? VK_COMPARE_OP_GREATER : VK_COMPARE_OP_LESS;
  VkPipelineColorBlendAttachmentState blend{};
  blend.colorWriteMask = composite ? 0 : 0xF;
  VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  cb.attachmentCount = 1;
  cb.pAttachments = &blend;
  VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  info.stageCount = 2;
  info.pStages = stages;
  info.pVertexInputState = &input;
  info.pInputAssemblyState = &assembly;
  info.pViewportState = &vp;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &ms;
  info.pDepthStencilState = &ds;
  info.pColorBlendState = &cb;
  info.layout = pipelineLayout;
  info.renderPass = pass;
  VkPipeline pipeline;
  check(vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline), "vkCreateGraphicsPipelines");
  vkDestroyShaderModule(device, vert, nullptr);
  vkDestroyShaderModule(device, frag, nullptr);
  return pipeline;
}

void SceneRenderer::State::label(const char* text, bool begin) {
  if (!debugUtils) return;
  if (begin) {
    auto fn = reinterpret_cast<PFN_vkCmdBeginDebugUtilsLabelEXT>(
        vkGetInstanceProcAddr(instance, "vkCmdBeginDebugUtilsLabelEXT"));
    VkDebugUtilsLabelEXT l{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT};
    l.pLabelName = text;
    fn(cmd, &l);
  } else {
    auto fn = reinterpret_cast<PFN_vkCmdEndDebugUtilsLabelEXT>(
        vkGetInstanceProcAddr(instance, "vkCmdEndDebugUtilsLabelEXT"));
    fn(cmd);
  }
}

void SceneRenderer::State::record(const Camera& camera) {
  // The uniform block: view column-major, projection row-major (as scene.vert declares them). With
  // GL's depth row (row2 = 2 row2 - row3), the shader's own remap gives back the Vulkan projection.
  glm::mat4 held = camera.projection;
  if (o.glDepthRow)
    for (int column = 0; column < 4; ++column) held[column][2] = 2.0f * camera.projection[column][2] - camera.projection[column][3];
  const glm::mat4 projectionRows = glm::transpose(held);
  auto* u = static_cast<uint8_t*>(uniforms.mapped);
  std::memcpy(u, glm::value_ptr(camera.view), 64);
  std::memcpy(u + 64, glm::value_ptr(projectionRows), 64);
  const float tint[4] = {1, 1, 1, 1};
  std::memcpy(u + 128, tint, 16);
  const glm::mat4 light = glm::perspectiveRH_ZO(glm::radians(90.0f), 1.0f, 0.5f, 20.0f);
  std::memcpy(u + 144, glm::value_ptr(light), 64);
  const glm::mat4 viewProjection = camera.projection * camera.view;
  const glm::mat4 modelViewProjection = viewProjection * sceneModel();
  const glm::mat4 inverseModel = glm::inverse(sceneModel());
  std::memcpy(u + 208, glm::value_ptr(viewProjection), 64);
  std::memcpy(u + 272, glm::value_ptr(modelViewProjection), 64);
  std::memcpy(u + 336, glm::value_ptr(inverseModel), 64);
  std::memcpy(u + 400, glm::value_ptr(camera.view), 64);  // columns[0..3]
  std::memcpy(u + 464, glm::value_ptr(camera.projection), 64);  // columns[4..7]
  glm::mat4 push[2] = {camera.view, camera.projection};

  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vkBeginCommandBuffer(cmd, &begin), "vkBeginCommandBuffer");
  VkClearValue clears[2];
  clears[0].color = {{0, 0, 0, 0}};
  clears[1].depthStencil = {farIsZero() ? 0.0f : 1.0f, 0};
  VkRenderPassBeginInfo rp{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  rp.renderPass = gbufferPass;
  rp.framebuffer = gbufferFramebuffer;
  rp.renderArea = {{0, 0}, {uint32_t(o.width), uint32_t(o.height)}};
  rp.clearValueCount = 2;
  rp.pClearValues = clears;
  VkDeviceSize offset = 0;
  label("gbuffer", true);
  vkCmdBeginRenderPass(cmd, &rp, VK_SUBPASS_CONTENTS_INLINE);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, gbufferPipeline);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelineLayout, 0, 1, &set, 0, nullptr);
  vkCmdBindVertexBuffers(cmd, 0, 1, &vertices.buffer, &offset);
  vkCmdPushConstants(cmd, pipelineLayout, VK_SHADER_STAGE_VERTEX_BIT, 0, kPushBytes, push);
  for (size_t i = 0; i + 1 < mesh.firstVertex.size(); ++i)
    vkCmdDraw(cmd, mesh.firstVertex[i + 1] - mesh.firstVertex[i], 1, mesh.firstVertex[i], 0);
  if (compositePipeline) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, compositePipeline);
    vkCmdDraw(cmd, mesh.firstVertex[1], 1, 0, 0);
  }
  vkCmdEndRenderPass(cmd);
  label(nullptr, false);

  label("overlay", true);  // a draw without a depth attachment, after the G-buffer
  rp.renderPass = overlayPass;
  rp.framebuffer = overlayFramebuffer;
  rp.clearValueCount = 1;
  vkCmdBeginRenderPass(cmd, &rp, VK_SUBPASS_CONTENTS_INLINE);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, overlayPipeline);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelineLayout, 0, 1, &set, 0, nullptr);
  vkCmdBindVertexBuffers(cmd, 0, 1, &vertices.buffer, &offset);
  vkCmdPushConstants(cmd, pipelineLayout, VK_SHADER_STAGE_VERTEX_BIT, 0, kPushBytes, push);
  vkCmdDraw(cmd, mesh.firstVertex[1], 1, 0, 0);
  vkCmdEndRenderPass(cmd);
  label(nullptr, false);

  VkBufferImageCopy copy{};
  copy.imageSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1};
  copy.imageExtent = {uint32_t(o.width), uint32_t(o.height), 1};
  vkCmdCopyImageToBuffer(cmd, readDepth().image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, depthReadback.buffer, 1, &copy);
  copy.imageSubresource.aspectMask = VK_IMAGE_ASPECT_COLOR_BIT;
  vkCmdCopyImageToBuffer(cmd, readNormals().image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, normalReadback.buffer, 1, &copy);
  VkMemoryBarrier toHost{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  toHost.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  toHost.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &toHost, 0, nullptr, 0,
                       nullptr);
  check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
}

void SceneRenderer::State::destroy() {
  if (!device) return;
  vkDeviceWaitIdle(device);
  vkDestroyFence(device, fence, nullptr);
  vkDestroyCommandPool(device, commandPool, nullptr);
  vkDestroyPipeline(device, gbufferPipeline, nullptr);
  vkDestroyPipeline(device, overlayPipeline, nullptr);
  if (compositePipeline) vkDestroyPipeline(device, compositePipeline, nullptr);
  vkDestroyPipelineLayout(device, pipelineLayout, nullptr);
  vkDestroyDescriptorPool(device, pool, nullptr);
  vkDestroyDescriptorSetLayout(device, setLayout, nullptr);
  for (Buffer* b : {&uniforms, &extra, &vertices, &depthReadback, &normalReadback}) {
    vkDestroyBuffer(device, b->buffer, nullptr);
    vkFreeMemory(device, b->memory, nullptr);
  }
  vkDestroyFramebuffer(device, gbufferFramebuffer, nullptr);
  vkDestroyFramebuffer(device, overlayFramebuffer, nullptr);
  vkDestroyRenderPass(device, gbufferPass, nullptr);
  vkDestroyRenderPass(device, overlayPass, nullptr);
  for (Image* i : {&depth, &normals, &overlay, &depthResolved, &normalsResolved}) {
    if (!i->image) continue;
    vkDestroyImageView(device, i->view, nullptr);
    vkDestroyImage(device, i->image, nullptr);
    vkFreeMemory(device, i->memory, nullptr);
  }
  vkDestroyDevice(device, nullptr);
  device = VK_NULL_HANDLE;
}

SceneRenderer::SceneRenderer(const RenderOptions& options) : s_(std::make_unique<State>()) {
  State& s = *s_;
  s.o = options;
  s.createInstance();
  s.createDevice();
  VkImageAspectFlags depthAspect = VK_IMAGE_ASPECT_DEPTH_BIT;
  if (hasStencil(options.depthFormat)) depthAspect |= VK_IMAGE_ASPECT_STENCIL_BIT;
  const VkImageUsageFlags depthUse = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  const VkImageUsageFlags colorUse = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  s.depth = s.createImage(options.depthFormat, depthUse, depthAspect, "gbuffer.depth", options.samples);
  s.normals = s.createImage(VK_FORMAT_R16G16B16A16_SFLOAT, colorUse, VK_IMAGE_ASPECT_COLOR_BIT, "gbuffer.normals",
                            options.samples);
  if (options.samples > 1) {
    s.depthResolved = s.createImage(options.depthFormat, depthUse, depthAspect, "gbuffer.depth_resolved");
    s.normalsResolved = s.createImage(VK_FORMAT_R16G16B16A16_SFLOAT, colorUse, VK_IMAGE_ASPECT_COLOR_BIT,
                                      "gbuffer.normals_resolved");
  }
  s.overlay = s.createImage(VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, VK_IMAGE_ASPECT_COLOR_BIT,
                            "overlay");
  s.gbufferPass = s.createRenderPass(true);
  s.overlayPass = s.createRenderPass(false);
  s.gbufferFramebuffer = s.createFramebuffer(s.gbufferPass, options.samples > 1
      ? std::vector<VkImageView>{s.normals.view, s.depth.view, s.normalsResolved.view, s.depthResolved.view}
      : std::vector<VkImageView>{s.normals.view, s.depth.view});
  s.overlayFramebuffer = s.createFramebuffer(s.overlayPass, {s.overlay.view});
  const size_t pixels = size_t(options.width) * size_t(options.height);
  s.uniforms = s.createBuffer(528, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
  s.extra = s.createBuffer(64, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  const glm::mat4 identity(1.0f);
  std::memcpy(s.extra.mapped, glm::value_ptr(identity), 64);
  s.vertices = s.createBuffer(s.mesh.vertices.size() * sizeof(Vertex), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
  std::memcpy(s.vertices.mapped, s.mesh.vertices.data(), s.mesh.vertices.size() * sizeof(Vertex));
  s.depthReadback = s.createBuffer(pixels * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  s.normalReadback = s.createBuffer(pixels * 8, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  s.createDescriptors();
  s.gbufferPipeline = s.createPipeline(s.gbufferPass, true);
  s.overlayPipeline = s.createPipeline(s.overlayPass, false);
  if (options.finalComposite) s.compositePipeline = s.createPipeline(s.gbufferPass, true, true);
  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  poolInfo.queueFamilyIndex = s.family;
  check(vkCreateCommandPool(s.device, &poolInfo, nullptr, &s.commandPool), "vkCreateCommandPool");
  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = s.commandPool;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  check(vkAllocateCommandBuffers(s.device, &alloc, &s.cmd), "vkAllocateCommandBuffers");
  VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  check(vkCreateFence(s.device, &fenceInfo, nullptr, &s.fence), "vkCreateFence");
}

SceneRenderer::~SceneRenderer() {
  s_->destroy();
  if (s_->messenger) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(s_->instance, "vkDestroyDebugUtilsMessengerEXT"));
    destroy(s_->instance, s_->messenger, nullptr);
  }
  if (s_->instance) vkDestroyInstance(s_->instance, nullptr);
}

VkInstance SceneRenderer::instance() const { return s_->instance; }
size_t SceneRenderer::validationMessages() const { return s_->validationMessages; }

FrameReadback SceneRenderer::renderFrame(const Camera& camera) {
  State& s = *s_;
  check(vkResetCommandBuffer(s.cmd, 0), "vkResetCommandBuffer");
  s.record(camera);
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &s.cmd;
  check(vkQueueSubmit(s.queue, 1, &submit, s.fence), "vkQueueSubmit");
  check(vkWaitForFences(s.device, 1, &s.fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  check(vkResetFences(s.device, 1, &s.fence), "vkResetFences");

  const size_t pixels = size_t(s.o.width) * size_t(s.o.height);
  const size_t texel = s.o.depthFormat == VK_FORMAT_D16_UNORM ? 2 : 4;
  FrameReadback out;
  out.depth.resize(pixels);
  for (size_t i = 0; i < pixels; ++i) {
    uint32_t raw = 0;
    std::memcpy(&raw, static_cast<const uint8_t*>(s.depthReadback.mapped) + i * texel, texel);
    out.depth[i] = depthTexelToFloat(s.o.depthFormat, raw);
  }
  out.normalsHalf.resize(pixels * 4);
  std::memcpy(out.normalsHalf.data(), s.normalReadback.mapped, pixels * 8);
  return out;
}

float depthTexelToFloat(VkFormat format, uint32_t raw) {
  switch (format) {
    case VK_FORMAT_D16_UNORM:
      return float(raw & 0xFFFFu) / 65535.0f;
    case VK_FORMAT_X8_D24_UNORM_PACK32:
    case VK_FORMAT_D24_UNORM_S8_UINT:
      return float(raw & 0xFFFFFFu) / 16777215.0f;
    default: {
      float f;
      std::memcpy(&f, &raw, 4);
      return f;
    }
  }
}

}  // namespace aor::rdtest
