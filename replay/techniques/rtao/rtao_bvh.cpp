#include "techniques/rtao/rtao_bvh.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

namespace aor {
namespace {

static_assert(sizeof(shader::RtaoBvhNode) == 32 && sizeof(shader::RtaoTriangle) == 48, "rtao.h's GPU layout");

// The builder's tree, in Embree's thread-local memory until it is flattened.
struct BuildNode {
  bool leaf = false;
  RTCBounds bounds[2]{};
  BuildNode* children[2]{};
  uint32_t primitives[shader::kRtaoMaxLeafTriangles]{};
  uint32_t count = 0;
};

void* createNode(RTCThreadLocalAllocator allocator, unsigned int childCount, void*) {
  if (childCount != 2) throw std::logic_error("rtcBuildBVH made a node of " + std::to_string(childCount) + " children");
  return new (rtcThreadLocalAlloc(allocator, sizeof(BuildNode), 16)) BuildNode{};
}

void setChildren(void* node, void** children, unsigned int childCount, void*) {
  for (unsigned int k = 0; k < childCount; ++k) static_cast<BuildNode*>(node)->children[k] = static_cast<BuildNode*>(children[k]);
}

void setBounds(void* node, const RTCBounds** bounds, unsigned int childCount, void*) {
  for (unsigned int k = 0; k < childCount; ++k) static_cast<BuildNode*>(node)->bounds[k] = *bounds[k];
}

void* createLeaf(RTCThreadLocalAllocator allocator, const RTCBuildPrimitive* primitives, size_t count, void*) {
  if (count > shader::kRtaoMaxLeafTriangles) throw std::logic_error("rtcBuildBVH made a leaf over maxLeafSize");
  auto* leaf = new (rtcThreadLocalAlloc(allocator, sizeof(BuildNode), 16)) BuildNode{};
  leaf->leaf = true;
  leaf->count = uint32_t(count);
  for (size_t k = 0; k < count; ++k) leaf->primitives[k] = primitives[k].primID;
  return leaf;
}

glm::vec3 vertex(const CaptureGeometry& g, uint32_t index) {
  return {g.positions[3 * size_t(index)], g.positions[3 * size_t(index) + 1], g.positions[3 * size_t(index) + 2]};
}

// Flattens the tree depth first: a node's two children take two adjacent slots.
class Flattener {
 public:
  Flattener(const CaptureGeometry& geometry, const std::vector<glm::uvec3>& kept, RtaoBvh& out)
      : geometry_(geometry), kept_(kept), out_(out) {}

  void fill(uint32_t slot, const BuildNode* node, const RTCBounds& bounds, uint32_t level) {
    out_.depth = std::max(out_.depth, level);
    if (level > shader::kRtaoMaxBvhDepth) throw std::logic_error("BVH deeper than the traversal stack");
    shader::RtaoBvhNode& n = out_.nodes[slot];
    n.lower = {bounds.lower_x, bounds.lower_y, bounds.lower_z};
    n.upper = {bounds.upper_x, bounds.upper_y, bounds.upper_z};
    if (node->leaf) {
      n.first = uint32_t(out_.triangles.size());
      n.count = node->count;
      for (uint32_t k = 0; k < node->count; ++k) out_.triangles.push_back(triangle(kept_[node->primitives[k]]));
      return;
    }
    uint32_t first = uint32_t(out_.nodes.size());
    out_.nodes.resize(out_.nodes.size() + 2);
    out_.nodes[slot].first = first;  // `n` may have moved with the resize
    out_.nodes[slot].count = 0;
    fill(first, node->children[0], node->bounds[0], level + 1);
    fill(first + 1, node->children[1], node->bounds[1], level + 1);
  }

 private:
  shader::RtaoTriangle triangle(const glm::uvec3& t) const {
    glm::vec3 a = vertex(geometry_, t.x), b = vertex(geometry_, t.y), c = vertex(geometry_, t.z);
    return {glm::vec4(a, 0.0f), glm::vec4(b - a, 0.0f), glm::vec4(c - a, 0.0f)};
  }
  const CaptureGeometry& geometry_;
  const std::vector<glm::uvec3>& kept_;
  RtaoBvh& out_;
};

}  // namespace

std::vector<glm::uvec3> rtaoKeptTriangles(const CaptureGeometry& geometry) {
  std::vector<glm::uvec3> kept;
  for (size_t t = 0; t < geometry.triangleCount(); ++t) {
    glm::uvec3 ix(geometry.indices[3 * t], geometry.indices[3 * t + 1], geometry.indices[3 * t + 2]);
    glm::vec3 a = vertex(geometry, ix.x), b = vertex(geometry, ix.y), c = vertex(geometry, ix.z);
    if (glm::length(glm::cross(b - a, c - a)) != 0.0f) kept.push_back(ix);
  }
  return kept;
}

RtaoBvh buildRtaoBvh(const CaptureGeometry& geometry) {
  std::vector<glm::uvec3> kept = rtaoKeptTriangles(geometry);
  std::vector<RTCBuildPrimitive> primitives;
  for (const glm::uvec3& ix : kept) {
    glm::vec3 a = vertex(geometry, ix.x), b = vertex(geometry, ix.y), c = vertex(geometry, ix.z);
    glm::vec3 lo = glm::min(a, glm::min(b, c)), hi = glm::max(a, glm::max(b, c));
    RTCBuildPrimitive p{};
    p.lower_x = lo.x, p.lower_y = lo.y, p.lower_z = lo.z;
    p.upper_x = hi.x, p.upper_y = hi.y, p.upper_z = hi.z;
    p.geomID = 0;
    p.primID = uint32_t(primitives.size());
    primitives.push_back(p);
  }
  if (kept.empty()) throw std::invalid_argument("buildRtaoBvh: no triangle with a non-zero area");
  RTCDevice device = rtcNewDevice("threads=1");
  if (!device) throw std::runtime_error("rtcNewDevice failed (Embree error " + std::to_string(rtcGetDeviceError(nullptr)) + ")");
  RTCBVH bvh = rtcNewBVH(device);
  RTCBuildArguments args = rtcDefaultBuildArguments();
  args.buildQuality = RTC_BUILD_QUALITY_MEDIUM;  // binned SAH; HIGH would add spatial splits (splitPrimitive)
  args.maxBranchingFactor = 2;
  args.maxDepth = shader::kRtaoMaxBvhDepth - 1;  // levels below the root
  args.maxLeafSize = shader::kRtaoMaxLeafTriangles;
  args.bvh = bvh;
  args.primitives = primitives.data();
  args.primitiveCount = primitives.size();
  args.primitiveArrayCapacity = primitives.size();
  args.createNode = createNode;
  args.setNodeChildren = setChildren;
  args.setNodeBounds = setBounds;
  args.createLeaf = createLeaf;
  // The root's bounds are not handed to a callback: the union of every primitive's.
  RTCBounds rootBounds{primitives[0].lower_x, primitives[0].lower_y, primitives[0].lower_z, 0.0f,
                       primitives[0].upper_x, primitives[0].upper_y, primitives[0].upper_z, 0.0f};
  for (const auto& p : primitives) {
    rootBounds.lower_x = std::min(rootBounds.lower_x, p.lower_x), rootBounds.upper_x = std::max(rootBounds.upper_x, p.upper_x);
    rootBounds.lower_y = std::min(rootBounds.lower_y, p.lower_y), rootBounds.upper_y = std::max(rootBounds.upper_y, p.upper_y);
    rootBounds.lower_z = std::min(rootBounds.lower_z, p.lower_z), rootBounds.upper_z = std::max(rootBounds.upper_z, p.upper_z);
  }
  RtaoBvh out;
  try {
    auto* root = static_cast<BuildNode*>(rtcBuildBVH(&args));
    if (!root) throw std::runtime_error("rtcBuildBVH failed (Embree error " + std::to_string(rtcGetDeviceError(device)) + ")");
    out.nodes.reserve(2 * kept.size());
    out.triangles.reserve(kept.size());
    out.nodes.resize(1);
    Flattener(geometry, kept, out).fill(0, root, rootBounds, 1);
  } catch (...) {
    rtcReleaseBVH(bvh);
    rtcReleaseDevice(device);
    throw;
  }
  rtcReleaseBVH(bvh);
  rtcReleaseDevice(device);
  return out;
}

}  // namespace aor
