#include "techniques/rtao/rtao_accel.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "techniques/rtao/rtao_bvh.h"
#include "vk/context.h"
#include "vk/vk_check.h"

namespace aor {
namespace {

// VK_KHR_acceleration_structure's entry points: extension functions, which the loader does not export.
struct AccelFunctions {
  PFN_vkGetAccelerationStructureBuildSizesKHR sizes = nullptr;
  PFN_vkCreateAccelerationStructureKHR create = nullptr;
  PFN_vkDestroyAccelerationStructureKHR destroy = nullptr;
  PFN_vkCmdBuildAccelerationStructuresKHR build = nullptr;
  PFN_vkGetAccelerationStructureDeviceAddressKHR address = nullptr;
};

AccelFunctions accelFunctions(const VulkanContext& vk) {
  if (!vk.enabled(kAccelerationStructureExtension))
    throw std::logic_error("rtao: acceleration structures on a context without VK_KHR_acceleration_structure enabled");
  auto get = [&](const char* name) { return vkGetDeviceProcAddr(vk.device, name); };
  AccelFunctions f;
  f.sizes = reinterpret_cast<PFN_vkGetAccelerationStructureBuildSizesKHR>(get("vkGetAccelerationStructureBuildSizesKHR"));
  f.create = reinterpret_cast<PFN_vkCreateAccelerationStructureKHR>(get("vkCreateAccelerationStructureKHR"));
  f.destroy = reinterpret_cast<PFN_vkDestroyAccelerationStructureKHR>(get("vkDestroyAccelerationStructureKHR"));
  f.build = reinterpret_cast<PFN_vkCmdBuildAccelerationStructuresKHR>(get("vkCmdBuildAccelerationStructuresKHR"));
  f.address = reinterpret_cast<PFN_vkGetAccelerationStructureDeviceAddressKHR>(get("vkGetAccelerationStructureDeviceAddressKHR"));
  if (!f.sizes || !f.create || !f.destroy || !f.build || !f.address)
    throw std::runtime_error("rtao: the device lacks an entry point of VK_KHR_acceleration_structure");
  return f;
}

// A buffer the build reaches by device address (its memory allocated with the device-address
// flag), host-visible and mapped when `host` (the build's inputs, written once), else device-local.
GpuBuffer addressableBuffer(const VulkanContext& vk, VkDeviceSize bytes, VkBufferUsageFlags usage, bool host) {
  GpuBuffer buffer = createBufferUnbound(vk, bytes, usage | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT);
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(vk.device, buffer.buffer, &req);
  VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
  flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
  VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, &flags};
  info.allocationSize = req.size;
  info.memoryTypeIndex = findMemoryType(vk, req.memoryTypeBits,
                                        host ? VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT
                                             : VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  VK_CHECK(vkAllocateMemory(vk.device, &info, nullptr, &buffer.memory));
  bindBuffer(vk, buffer, buffer.memory, 0);
  if (host) VK_CHECK(vkMapMemory(vk.device, buffer.memory, 0, VK_WHOLE_SIZE, 0, &buffer.mapped));
  return buffer;
}

GpuBuffer inputBuffer(const VulkanContext& vk, const void* data, VkDeviceSize bytes) {
  GpuBuffer buffer = addressableBuffer(vk, bytes, VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR, true);
  std::memcpy(buffer.mapped, data, bytes);
  return buffer;
}

VkDeviceAddress addressOf(const VulkanContext& vk, const GpuBuffer& buffer) {
  VkBufferDeviceAddressInfo info{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
  info.buffer = buffer.buffer;
  return vkGetBufferDeviceAddress(vk.device, &info);
}

// A structure of `build`'s type, sized for it with `primitives`, in its own device-local buffer;
// sets `build`'s destination and returns the scratch bytes its build needs.
VkDeviceSize createStructure(const VulkanContext& vk, const AccelFunctions& fn,
                             VkAccelerationStructureBuildGeometryInfoKHR& build, uint32_t primitives, GpuBuffer& storage,
                             uint64_t& bytes) {
  VkAccelerationStructureBuildSizesInfoKHR sizes{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
  fn.sizes(vk.device, VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &build, &primitives, &sizes);
  bytes = sizes.accelerationStructureSize;
  storage = addressableBuffer(vk, bytes, VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR, false);
  VkAccelerationStructureCreateInfoKHR info{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_CREATE_INFO_KHR};
  info.buffer = storage.buffer;
  info.size = bytes;
  info.type = build.type;
  VK_CHECK(fn.create(vk.device, &info, nullptr, &storage.accelerationStructure));
  build.dstAccelerationStructure = storage.accelerationStructure;
  return sizes.buildScratchSize;
}

VkDeviceAddress structureAddress(const VulkanContext& vk, const AccelFunctions& fn, VkAccelerationStructureKHR structure) {
  VkAccelerationStructureDeviceAddressInfoKHR info{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_DEVICE_ADDRESS_INFO_KHR};
  info.accelerationStructure = structure;
  return fn.address(vk.device, &info);
}

VkDeviceSize scratchAlignment(const VulkanContext& vk) {
  VkPhysicalDeviceAccelerationStructurePropertiesKHR accel{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_PROPERTIES_KHR};
  VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &accel};
  vkGetPhysicalDeviceProperties2(vk.physicalDevice, &props);
  return std::max<VkDeviceSize>(1, accel.minAccelerationStructureScratchOffsetAlignment);
}

// Records both builds: the BLAS, a barrier (the TLAS build reads the BLAS and reuses its scratch),
// the TLAS; submits them and waits.
void runBuilds(VulkanContext& vk, const AccelFunctions& fn, VkAccelerationStructureBuildGeometryInfoKHR& blas,
               uint32_t triangles, VkAccelerationStructureBuildGeometryInfoKHR& tlas) {
  runOneTimeCommands(vk, [&](VkCommandBuffer cmd) {
    VkAccelerationStructureBuildRangeInfoKHR blasRange{triangles, 0, 0, 0}, tlasRange{1, 0, 0, 0};
    const VkAccelerationStructureBuildRangeInfoKHR* blasRanges = &blasRange;
    const VkAccelerationStructureBuildRangeInfoKHR* tlasRanges = &tlasRange;
    fn.build(cmd, 1, &blas, &blasRanges);
    VkMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    barrier.srcStageMask = barrier.dstStageMask = VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR;
    barrier.srcAccessMask = VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR;
    barrier.dstAccessMask = VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR | VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR;
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.memoryBarrierCount = 1;
    dependency.pMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(cmd, &dependency);
    fn.build(cmd, 1, &tlas, &tlasRanges);
  });
}

}  // namespace

RtaoAccel buildRtaoAccel(VulkanContext& vk, const CaptureGeometry& geometry) {
  AccelFunctions fn = accelFunctions(vk);
  std::vector<glm::uvec3> kept = rtaoKeptTriangles(geometry);
  if (kept.empty()) throw std::invalid_argument("buildRtaoAccel: no triangle with a non-zero area");
  static_assert(sizeof(glm::uvec3) == 3 * sizeof(uint32_t), "indices are three packed words");
  RtaoAccel out;
  out.triangleCount = kept.size();
  GpuBuffer vertices = inputBuffer(vk, geometry.positions.data(), geometry.positions.size() * sizeof(float));
  GpuBuffer indices = inputBuffer(vk, kept.data(), kept.size() * sizeof(glm::uvec3));

  VkAccelerationStructureGeometryKHR triangles{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
  triangles.geometryType = VK_GEOMETRY_TYPE_TRIANGLES_KHR;
  triangles.flags = VK_GEOMETRY_OPAQUE_BIT_KHR;  // every candidate is a hit: no any-hit step, as the compute path
  auto& t = triangles.geometry.triangles;
  t.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_TRIANGLES_DATA_KHR;
  t.vertexFormat = VK_FORMAT_R32G32B32_SFLOAT;
  t.vertexData.deviceAddress = addressOf(vk, vertices);
  t.vertexStride = 3 * sizeof(float);
  t.maxVertex = uint32_t(geometry.vertexCount() - 1);
  t.indexType = VK_INDEX_TYPE_UINT32;
  t.indexData.deviceAddress = addressOf(vk, indices);
  VkAccelerationStructureBuildGeometryInfoKHR blas{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
  blas.type = VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR;
  blas.flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR;
  blas.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
  blas.geometryCount = 1;
  blas.pGeometries = &triangles;
  VkDeviceSize scratchBytes = createStructure(vk, fn, blas, uint32_t(kept.size()), out.blas, out.blasBytes);

  VkAccelerationStructureInstanceKHR instance{};
  instance.transform.matrix[0][0] = instance.transform.matrix[1][1] = instance.transform.matrix[2][2] = 1.0f;
  instance.mask = 0xff;
  instance.flags = VK_GEOMETRY_INSTANCE_TRIANGLE_FACING_CULL_DISABLE_BIT_KHR;  // two-sided, as the compute path
  instance.accelerationStructureReference = structureAddress(vk, fn, out.blas.accelerationStructure);
  GpuBuffer instances = inputBuffer(vk, &instance, sizeof(instance));
  VkAccelerationStructureGeometryKHR instanceGeometry{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
  instanceGeometry.geometryType = VK_GEOMETRY_TYPE_INSTANCES_KHR;
  instanceGeometry.geometry.instances.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_INSTANCES_DATA_KHR;
  instanceGeometry.geometry.instances.data.deviceAddress = addressOf(vk, instances);
  VkAccelerationStructureBuildGeometryInfoKHR tlas = blas;
  tlas.type = VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR;
  tlas.pGeometries = &instanceGeometry;
  scratchBytes = std::max(scratchBytes, createStructure(vk, fn, tlas, 1, out.tlas, out.tlasBytes));

  // One scratch buffer for both builds, its address aligned as the device asks.
  VkDeviceSize alignment = scratchAlignment(vk);
  GpuBuffer scratch = addressableBuffer(vk, scratchBytes + alignment, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, false);
  VkDeviceAddress scratchAddress = (addressOf(vk, scratch) + alignment - 1) / alignment * alignment;
  blas.scratchData.deviceAddress = tlas.scratchData.deviceAddress = scratchAddress;
  out.buildBytes = vertices.size + indices.size + instances.size + scratch.size;
  runBuilds(vk, fn, blas, uint32_t(kept.size()), tlas);
  for (GpuBuffer* b : {&vertices, &indices, &instances, &scratch}) destroyBuffer(vk, *b);
  return out;
}

void destroyRtaoAccel(VulkanContext& vk, RtaoAccel& accel) {
  AccelFunctions fn = accelFunctions(vk);
  for (GpuBuffer* b : {&accel.tlas, &accel.blas}) {
    if (b->accelerationStructure) fn.destroy(vk.device, b->accelerationStructure, nullptr);
    b->accelerationStructure = VK_NULL_HANDLE;
    destroyBuffer(vk, *b);
  }
}

}  // namespace aor
