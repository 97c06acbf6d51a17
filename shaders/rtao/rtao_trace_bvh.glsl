// The compute path's traversal of the trace pass (rtao_body.glsl): a stack traversal of the BVH that
// replay/techniques/rtao/rtao_bvh.cpp built and flattened, in two storage buffers (bindings 2 and 3).
layout(set = 0, binding = 2, scalar) readonly buffer Nodes { RtaoBvhNode nodes[]; };
layout(set = 0, binding = 3, scalar) readonly buffer Triangles { RtaoTriangle triangles[]; };
#define RTAO_SCENE_BINDINGS 2

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
