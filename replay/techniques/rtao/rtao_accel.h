#pragma once
// The ray-query path's acceleration structures, as seed 003 builds them: one bottom-level structure
// of the capture's triangles (exactly those the compute BVH holds, rtaoKeptTriangles, opaque) and a
// top-level one with a single instance of it under the identity transform. Built once per capture
// on the device (VK_KHR_acceleration_structure, prefer fast trace, not compacted) and kept for the
// replay; the build's inputs and scratch are freed when it has finished.
#include <cstdint>

#include "capture/obj_geometry.h"
#include "vk/resources.h"

namespace aor {

struct RtaoAccel {
  GpuBuffer blas, tlas;  // each holds its structure (GpuBuffer::accelerationStructure); the pass binds tlas's
  uint64_t blasBytes = 0, tlasBytes = 0;  // the structures' sizes (vkGetAccelerationStructureBuildSizesKHR)
  uint64_t buildBytes = 0;                // vertices, indices, instance and scratch, freed after the build
  size_t triangleCount = 0;
  uint64_t bytes() const { return blasBytes + tlasBytes; }
};

// Needs a context with VK_KHR_acceleration_structure enabled (VulkanContext::enabled). Returns when
// the device has finished the build.
RtaoAccel buildRtaoAccel(VulkanContext& vk, const CaptureGeometry& geometry);
void destroyRtaoAccel(VulkanContext& vk, RtaoAccel& accel);

}  // namespace aor
