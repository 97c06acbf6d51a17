// Seed 003's compute shader, with a compute-shader BVH traversal in place of the ray query: per
// pixel, the world position from the linear distance, the normal (the capture's or the front's
// reconstructed one), `samples` cosine-weighted rays from OffsetRay's origin, TEA-seeded PCG
// numbers, binary or distance-weighted occlusion, `power`, then the running mean with last
// frame's accumulation (RTAO_ACCUMULATE 1) or a fresh one (0: no previous binding at all).
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
layout(set = 0, binding = 2, scalar) readonly buffer Nodes { RtaoBvhNode nodes[]; };
layout(set = 0, binding = 3, scalar) readonly buffer Triangles { RtaoTriangle triangles[]; };
#if RTAO_ACCUMULATE
layout(set = 0, binding = 4, r32f) uniform readonly image2D previousMean;
layout(set = 0, binding = 5, r32f) uniform writeonly image2D mean;
#else
layout(set = 0, binding = 4, r32f) uniform writeonly image2D mean;
#endif

// Entry distance of the ray into the box, or a value beyond tFar when it misses.
float slabEntry(vec3 origin, vec3 inverseDirection, vec3 lower, vec3 upper, float tFar) {
  vec3 t0 = (lower - origin) * inverseDirection, t1 = (upper - origin) * inverseDirection;
  vec3 near = min(t0, t1), far = max(t0, t1);
  float entry = max(max(near.x, near.y), max(near.z, 0.0));
  float exit = min(min(far.x, far.y), min(far.z, tFar));
  return entry <= exit ? entry : tFar + 1.0;
}

// Moeller-Trumbore, two-sided: t of the hit in (0, tFar), else tFar + 1.
float intersectTriangle(vec3 origin, vec3 direction, RtaoTriangle tri, float tFar) {
  vec3 p = cross(direction, tri.edge2.xyz);
  float det = dot(tri.edge1.xyz, p);
  if (det == 0.0) return tFar + 1.0;
  float inverseDet = 1.0 / det;
  vec3 s = origin - tri.v0.xyz;
  float u = dot(s, p) * inverseDet;
  if (u < 0.0 || u > 1.0) return tFar + 1.0;
  vec3 q = cross(s, tri.edge1.xyz);
  float v = dot(direction, q) * inverseDet;
  if (v < 0.0 || u + v > 1.0) return tFar + 1.0;
  float t = dot(tri.edge2.xyz, q) * inverseDet;
  return t > 0.0 && t < tFar ? t : tFar + 1.0;
}

// The seed's TraceRay: 0 when nothing is hit within the radius, else 1 (binary) or 1 - t / radius
// of the closest hit (distance-based). Binary rays stop at the first hit, as
// gl_RayFlagsTerminateOnFirstHitEXT.
float traceOcclusion(vec3 origin, vec3 direction) {
  // A zero component would make 0 * inf = NaN in the slab test: a tiny one instead.
  vec3 inverseDirection = 1.0 / mix(direction, vec3(1e-20), lessThan(abs(direction), vec3(1e-20)));
  float closest = pc.radius;
  bool hit = false;
  uint stack[kRtaoMaxBvhDepth];
  uint depth = 0u;
  if (slabEntry(origin, inverseDirection, nodes[0].lower, nodes[0].upper, closest) <= closest) stack[depth++] = 0u;
  while (depth > 0u) {
    RtaoBvhNode node = nodes[stack[--depth]];
    if (node.count > 0u) {
      for (uint k = 0u; k < node.count; ++k) {
        float t = intersectTriangle(origin, direction, triangles[node.first + k], closest);
        if (t < closest) {
          closest = t;
          hit = true;
          if (!kDistanceBased) return 1.0;
        }
      }
      continue;
    }
    RtaoBvhNode a = nodes[node.first], b = nodes[node.first + 1u];
    float ta = slabEntry(origin, inverseDirection, a.lower, a.upper, closest);
    float tb = slabEntry(origin, inverseDirection, b.lower, b.upper, closest);
    uint nearChild = ta <= tb ? node.first : node.first + 1u, farChild = ta <= tb ? node.first + 1u : node.first;
    if (max(ta, tb) <= closest) stack[depth++] = farChild;  // the far one first: the near one pops next
    if (min(ta, tb) <= closest) stack[depth++] = nearChild;
  }
  if (!hit) return 0.0;
  return kDistanceBased ? 1.0 - closest / pc.radius : 1.0;
}

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
