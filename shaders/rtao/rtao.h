#ifndef AOR_RTAO_H
#define AOR_RTAO_H
// Seed 003 (ray-traced AO from the G-buffer, accumulated over frames): the trace pass's constants,
// the BVH's GPU layout and the CPU-checkable pieces of the math (random numbers, ray offset,
// hemisphere sampling), shared by rtao.comp and replay/techniques/rtao/.
#include "../common/common.h"
#include "../common/shared_begin.h"

// Specialisation constant ids of rtao_*.comp.
AOR_CONST int kRtaoSpecSamples = 0;        // rays per pixel per frame (AoControl::rtao_samples)
AOR_CONST int kRtaoSpecDistanceBased = 1;  // 1: occlusion 1 - t / radius of the closest hit; 0: any hit is 1
AOR_CONST int kRtaoSpecWorldNormals = 2;   // 1: the capture's world normals; 0: the front's view-space ones

// Deepest BVH the builder makes (RTCBuildArguments::maxDepth) and so the traversal stack's size.
AOR_CONST uint kRtaoMaxBvhDepth = 48u;
// Triangles per leaf at most (RTCBuildArguments::maxLeafSize).
AOR_CONST uint kRtaoMaxLeafTriangles = 4u;

// One BVH node, 32 bytes. Inner nodes (count == 0): children at first and first + 1. Leaves:
// triangles [first, first + count) of the triangle buffer.
struct RtaoBvhNode {
  vec3 lower;
  uint first;
  vec3 upper;
  uint count;
};
// One triangle, 48 bytes: a vertex and the two edges from it (w unused).
struct RtaoTriangle {
  vec4 v0;
  vec4 edge1;
  vec4 edge2;
};

struct RtaoConstants {
  vec4 viewToWorld0;  // rows of the view->world matrix (inverse of the capture's view)
  vec4 viewToWorld1;
  vec4 viewToWorld2;
  vec2 ndcToViewMul;
  vec2 ndcToViewAdd;
  vec2 invSize;
  ivec2 size;
  float radius;          // ray length, world units (AoControl::rtao_radius)
  float power;           // AoControl::rtao_power
  float normalOffset;    // world units per unit of view distance the origin moves along the normal first
  float newWeight;       // 1 / frames accumulated including this one: mix(previous, this frame, newWeight)
  uint frameNumber;      // the seed's frame: frames accumulated before this one (0 after a reset)
  uint hold;             // 1: max_frames reached, the mean is copied unchanged and no ray is traced
};

// TEA (Wheeler and Needham 1994) with 16 rounds, as a hash of two words: the seed's per-pixel,
// per-frame seed of the random sequence.
AOR_FUNC uint rtaoTea(uint value0, uint value1) {
  uint v0 = value0, v1 = value1, sum = 0u;
  for (uint round = 0u; round < 16u; ++round) {
    sum += 0x9e3779b9u;
    v0 += ((v1 << 4u) + 0xa341316cu) ^ (v1 + sum) ^ ((v1 >> 5u) + 0xc8013ea4u);
    v1 += ((v0 << 4u) + 0xad90777du) ^ (v0 + sum) ^ ((v0 >> 5u) + 0x7e95761eu);
  }
  return v0;
}

// PCG (O'Neill 2014), the RXS-M-XS output of a 32-bit LCG: advances `state`, returns 32 bits.
AOR_FUNC uint rtaoPcg(AOR_INOUT(uint) state) {
  uint previous = state * 747796405u + 2891336453u;
  uint word = ((previous >> ((previous >> 28u) + 4u)) ^ previous) * 277803737u;
  state = previous;
  return (word >> 22u) ^ word;
}

// Uniform in [0, 1] (the seed's rnd: 32 bits over 2^32 - 1).
AOR_FUNC float rtaoRandom(AOR_INOUT(uint) state) { return float(rtaoPcg(state)) / float(0xffffffffu); }

// Cosine-weighted direction around +Z from two uniform numbers (the seed's sampling).
AOR_FUNC vec3 rtaoCosineDirection(float r1, float r2) {
  float s = sqrt(1.0f - r2), phi = 2.0f * kPi * r1;
  return vec3(cos(phi) * s, sin(phi) * s, sqrt(r2));
}

// An orthonormal basis (tangent, bitangent) around unit n (Duff et al. 2017, "Building an
// orthonormal basis, revisited"): any basis gives the same distribution of directions.
AOR_FUNC void rtaoBasis(vec3 n, AOR_OUT(vec3) tangent, AOR_OUT(vec3) bitangent) {
  float sign = n.z >= 0.0f ? 1.0f : -1.0f;
  float a = -1.0f / (sign + n.z);
  float b = n.x * n.y * a;
  tangent = vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
  bitangent = vec3(b, sign + n.y * n.y * a, -n.y);
}

#ifndef __cplusplus
// Ray Tracing Gems ch. 6 (Waechter and Binder, "A Fast and Robust Method for Avoiding
// Self-Intersection"): moves p off the surface along n by a fixed number of float ulps (a fixed
// distance near the origin, where ulps vanish).
vec3 rtaoOffsetRay(vec3 p, vec3 n) {
  const float kOrigin = 1.0f / 32.0f, kFloatScale = 1.0f / 65536.0f, kIntScale = 256.0f;
  ivec3 offset = ivec3(kIntScale * n);
  vec3 moved = intBitsToFloat(floatBitsToInt(p) + ivec3(p.x < 0.0f ? -offset.x : offset.x, p.y < 0.0f ? -offset.y : offset.y,
                                                        p.z < 0.0f ? -offset.z : offset.z));
  return vec3(abs(p.x) < kOrigin ? p.x + kFloatScale * n.x : moved.x, abs(p.y) < kOrigin ? p.y + kFloatScale * n.y : moved.y,
              abs(p.z) < kOrigin ? p.z + kFloatScale * n.z : moved.z);
}
#endif

#include "../common/shared_end.h"
#endif
