// Seed 003's compute shader, its traversal chosen at compile time: per pixel, the world position
// from the linear distance, the normal (the capture's or the front's reconstructed one), `samples`
// cosine-weighted rays from OffsetRay's origin, TEA-seeded PCG numbers, binary or distance-weighted
// occlusion, `power`, then the running mean with last frame's accumulation (RTAO_ACCUMULATE 1) or a
// fresh one (0: no previous binding at all). The rays are the same whichever traversal runs them
// (RTAO_RAY_QUERY 0: the BVH in rtao_trace_bvh.glsl, 1: ray queries in rtao_trace_rayquery.glsl);
// each defines traceOcclusion and the number of bindings it takes from 2 on, RTAO_SCENE_BINDINGS.
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_control_flow_attributes : require
#include "rtao.h"

layout(local_size_x = kWorkgroupSize, local_size_y = kWorkgroupSize) in;
layout(constant_id = kRtaoSpecSamples) const int kSamples = 4;
layout(constant_id = kRtaoSpecDistanceBased) const bool kDistanceBased = true;
layout(constant_id = kRtaoSpecWorldNormals) const bool kWorldNormals = true;
layout(push_constant, scalar) uniform Push { RtaoConstants pc; };
layout(set = 0, binding = 0, r32f) uniform readonly image2D distanceImage;  // view distance along -Z, sky -1
layout(set = 0, binding = 1, rgba16f) uniform readonly image2D normals;    // world (captured) or view space
#if RTAO_RAY_QUERY
#include "rtao_trace_rayquery.glsl"
#else
#include "rtao_trace_bvh.glsl"
#endif
#if RTAO_ACCUMULATE
layout(set = 0, binding = 2 + RTAO_SCENE_BINDINGS, r32f) uniform readonly image2D previousMean;
layout(set = 0, binding = 3 + RTAO_SCENE_BINDINGS, r32f) uniform writeonly image2D mean;
#else
layout(set = 0, binding = 2 + RTAO_SCENE_BINDINGS, r32f) uniform writeonly image2D mean;
#endif

vec3 worldNormal(ivec2 pixel) {
  vec3 n = imageLoad(normals, pixel).xyz;
  if (!kWorldNormals) n = vec3(dot(pc.viewToWorld0.xyz, n), dot(pc.viewToWorld1.xyz, n), dot(pc.viewToWorld2.xyz, n));
  return normalize(n);
}

float frameVisibility(ivec2 pixel) {
  float dist = imageLoad(distanceImage, pixel).r;
  if (!(dist > 0.0)) return 1.0;  // sky: no surface, no occlusion
  vec3 n = worldNormal(pixel);
  if (any(isnan(n))) return 1.0;  // a zero or invalid normal: nothing to orient the hemisphere by
  vec3 view = viewPositionFromNdc(pixelToNdc(vec2(pixel), pc.invSize), dist, pc.ndcToViewMul, pc.ndcToViewAdd);
  vec4 v = vec4(view, 1.0);
  vec3 world = vec3(dot(pc.viewToWorld0, v), dot(pc.viewToWorld1, v), dot(pc.viewToWorld2, v));
  // The depth buffer's position is within its precision of the surface, not on it (the seed's
  // G-buffer holds the rasterised position): the generator's normal offset first, then OffsetRay.
  vec3 origin = rtaoOffsetRay(world + n * (pc.normalOffset * max(1.0, dist)), n);
  vec3 tangent, bitangent;
  rtaoBasis(n, tangent, bitangent);
  uint seed = rtaoTea(uint(pc.size.x) * uint(pixel.y) + uint(pixel.x), pc.frameNumber);
  float occlusion = 0.0;
  for (int i = 0; i < kSamples; ++i) {
    float r1 = rtaoRandom(seed), r2 = rtaoRandom(seed);
    vec3 local = rtaoCosineDirection(r1, r2);
    vec3 direction = local.x * tangent + local.y * bitangent + local.z * n;
    occlusion += traceOcclusion(origin, direction);
  }
  // The seed's ao.comp: visibility from the mean occlusion, then the power.
  float visibility = 1.0 - occlusion / float(kSamples);
  return pow(clamp(visibility, 0.0, 1.0), pc.power);
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= pc.size.x || pixel.y >= pc.size.y) return;
#if RTAO_ACCUMULATE
  float previous = imageLoad(previousMean, pixel).r;
  if (pc.hold != 0u) {
    imageStore(mean, pixel, vec4(previous));
    return;
  }
  imageStore(mean, pixel, vec4(mix(previous, frameVisibility(pixel), pc.newWeight)));
#else
  imageStore(mean, pixel, vec4(frameVisibility(pixel)));
#endif
}
