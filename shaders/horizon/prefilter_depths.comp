#version 450
// XeGTAO pass 1 (XeGTAO_PrefilterDepths16x16): the capture's depth to view z, and the 5-level MIP
// chain of it with XeGTAO's weighted-average filter, in one dispatch: each 8x8 workgroup covers
// 16x16 pixels, each thread 2x2 of them; levels 2-4 reduce through shared memory.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "horizon.h"

layout(local_size_x = kHorizonWorkgroupSize, local_size_y = kHorizonWorkgroupSize) in;
layout(push_constant, scalar) uniform Push {
  HorizonConstants pc;
  int mipLevels;  // levels the chain has: fewer than 5 for frames under 16 pixels a side
};
layout(set = 0, binding = 0) uniform sampler2D screenDepth;  // the capture's depth, nearest, clamped
// The chain's levels, R16F (or R32F with depth32=1): written without a format.
layout(set = 0, binding = 1) uniform writeonly image2D depthMip0;
layout(set = 0, binding = 2) uniform writeonly image2D depthMip1;
layout(set = 0, binding = 3) uniform writeonly image2D depthMip2;
layout(set = 0, binding = 4) uniform writeonly image2D depthMip3;
layout(set = 0, binding = 5) uniform writeonly image2D depthMip4;

#include "horizon_common.glsl"

shared float scratchDepths[8][8];

// XeGTAO_DepthMIPFilter's falloff over 0.75 x the effect radius: weight = saturate(d * mul + add).
// The same for every call: computed once per thread (four calls, two divisions each otherwise).
float falloffMul, falloffAdd;
void setMipFilterFalloff() {
  float effectRadius = 0.75 * pc.effectRadius * pc.radiusMultiplier;
  float falloffRange = pc.effectFalloffRange * effectRadius;
  float falloffFrom = effectRadius * (1.0 - pc.effectFalloffRange);
  falloffMul = -1.0 / falloffRange;
  falloffAdd = falloffFrom / falloffRange + 1.0;
}

// XeGTAO_DepthMIPFilter: the average of four depths, each weighted down the farther it lies
// behind the nearest.
float mipFilter(float d0, float d1, float d2, float d3) {
  float maxDepth = max(max(d0, d1), max(d2, d3));
  float w0 = clamp((maxDepth - d0) * falloffMul + falloffAdd, 0.0, 1.0);
  float w1 = clamp((maxDepth - d1) * falloffMul + falloffAdd, 0.0, 1.0);
  float w2 = clamp((maxDepth - d2) * falloffMul + falloffAdd, 0.0, 1.0);
  float w3 = clamp((maxDepth - d3) * falloffMul + falloffAdd, 0.0, 1.0);
  float weightSum = w0 + w1 + w2 + w3;
  return (w0 * d0 + w1 * d1 + w2 * d2 + w3 * d3) / weightSum;
}

// XeGTAO writes every texel of the 16x16 tile; a storage write outside the image is undefined in
// Vulkan, so each is bounded by its level's size (and a level the chain lacks is bound to its last
// and never written). A workgroup whose tile lies inside the frame with all five levels present
// (every one but the right and bottom edges' at 1080p) stores without the tests: `wholeTile` is
// the same for the whole workgroup, so the branch costs nothing where XeGTAO has none.
bool wholeTile;
// One vector comparison, no short-circuit: glslang turns each `&&` into a branch.
bool inLevel(int mip, ivec2 texel) {
  if (wholeTile) return true;
  ivec2 size = max(pc.viewportSize >> mip, ivec2(1));
  return all(lessThan(ivec3(texel, mip), ivec3(size, mipLevels)));
}

// One reduction step of levels 2-4 (XeGTAO's three `if (groupThreadID % k == 0)` blocks): threads
// on a `stride` grid reduce the 2x2 of scratch values `stride / 2` apart.
bool reduceStep(uvec2 thread, uint stride, out float value) {
  value = 0.0;
  if (any(notEqual(thread % stride, uvec2(0u)))) return false;  // XeGTAO's all(groupThreadID % k == 0)
  uint half_ = stride / 2u;
  value = mipFilter(scratchDepths[thread.x][thread.y], scratchDepths[thread.x + half_][thread.y],
                    scratchDepths[thread.x][thread.y + half_], scratchDepths[thread.x + half_][thread.y + half_]);
  scratchDepths[thread.x][thread.y] = value;
  return true;
}

void main() {
  setMipFilterFalloff();
  ivec2 tileEnd = ivec2(gl_WorkGroupID.xy + 1u) * int(2u * kHorizonWorkgroupSize);
  wholeTile = all(lessThanEqual(ivec3(tileEnd, kHorizonDepthMipLevels), ivec3(pc.viewportSize, mipLevels)));
  uvec2 base = gl_GlobalInvocationID.xy;
  uvec2 thread = gl_LocalInvocationID.xy;
  ivec2 pixel = ivec2(base * 2u);
  // The 2x2 quad whose top-left is `pixel`: gather at its centre (w, z, x, y = TL, TR, BL, BR).
  vec4 quad = textureGatherOffset(screenDepth, vec2(pixel) * pc.viewportPixelSize, ivec2(1, 1));
  vec4 screenDepths = quad.wzxy;  // TL, TR, BL, BR
  vec4 viewZ = horizonUnclampedViewDepth(screenDepths);
  vec4 depths = horizonClampDepth(viewZ);
  float d0 = depths.x, d1 = depths.y, d2 = depths.z, d3 = depths.w;
  if (inLevel(0, pixel)) imageStore(depthMip0, pixel, vec4(d0));
  if (inLevel(0, pixel + ivec2(1, 0))) imageStore(depthMip0, pixel + ivec2(1, 0), vec4(d1));
  if (inLevel(0, pixel + ivec2(0, 1))) imageStore(depthMip0, pixel + ivec2(0, 1), vec4(d2));
  if (inLevel(0, pixel + ivec2(1, 1))) imageStore(depthMip0, pixel + ivec2(1, 1), vec4(d3));

  float mip1 = mipFilter(d0, d1, d2, d3);
  if (inLevel(1, ivec2(base))) imageStore(depthMip1, ivec2(base), vec4(mip1));
  scratchDepths[thread.x][thread.y] = mip1;
  barrier();

  float value;
  if (reduceStep(thread, 2u, value) && inLevel(2, ivec2(base / 2u))) imageStore(depthMip2, ivec2(base / 2u), vec4(value));
  barrier();
  if (reduceStep(thread, 4u, value) && inLevel(3, ivec2(base / 4u))) imageStore(depthMip3, ivec2(base / 4u), vec4(value));
  barrier();
  if (reduceStep(thread, 8u, value) && inLevel(4, ivec2(base / 8u))) imageStore(depthMip4, ivec2(base / 8u), vec4(value));
}
