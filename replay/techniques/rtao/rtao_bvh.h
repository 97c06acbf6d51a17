#pragma once
// The BVH seed 003's rays traverse in a compute shader (the universal path: no ray-query
// extension needed): built once per capture on the CPU with Embree's rtcBuildBVH (binned SAH,
// two children per node) through our own node and leaf callbacks, then flattened into the
// storage-buffer layout of shaders/rtao/rtao.h (children of a node side by side, root at 0,
// triangles in leaf order).
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "capture/obj_geometry.h"
#include "rtao/rtao.h"

namespace aor {

struct RtaoBvh {
  std::vector<shader::RtaoBvhNode> nodes;
  std::vector<shader::RtaoTriangle> triangles;
  uint32_t depth = 0;  // levels from the root to the deepest leaf, root = 1
  uint64_t bytes() const { return nodes.size() * sizeof(nodes[0]) + triangles.size() * sizeof(triangles[0]); }
};

// The triangles both traversal paths trace (the BVH's leaves, the ray-query path's BLAS): the
// geometry's, in its order, less the degenerate ones (zero area, never hit). Three vertex indices each.
std::vector<glm::uvec3> rtaoKeptTriangles(const CaptureGeometry& geometry);

// Deterministic: one build thread, so the same geometry gives the same bytes on every machine.
// Degenerate triangles (zero area, never hit) are left out.
RtaoBvh buildRtaoBvh(const CaptureGeometry& geometry);

}  // namespace aor
