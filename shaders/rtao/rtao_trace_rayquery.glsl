// The ray-query path's traversal of the trace pass (rtao_body.glsl), as seed 003 traces: the
// capture's triangles in a BLAS under a one-instance TLAS (binding 2), built in prepare
// (replay/techniques/rtao/rtao_accel.cpp). The ray is the compute path's: the same origin and
// direction, t from 0 to the radius. The geometry is opaque, so the implementation commits every
// triangle it finds and the loop only drives the traversal; no face is culled (two-sided, as the
// compute path's Moeller-Trumbore).
layout(set = 0, binding = 2) uniform accelerationStructureEXT scene;
#define RTAO_SCENE_BINDINGS 1

// The seed's TraceRay: 0 when nothing is hit within the radius, else 1 (binary) or 1 - t / radius
// of the closest hit (distance-based). Binary rays stop at the first hit
// (gl_RayFlagsTerminateOnFirstHitEXT), as the seed's.
float traceOcclusion(vec3 origin, vec3 direction) {
  uint flags = gl_RayFlagsOpaqueEXT | (kDistanceBased ? 0u : gl_RayFlagsTerminateOnFirstHitEXT);
  rayQueryEXT query;
  rayQueryInitializeEXT(query, scene, flags, 0xffu, origin, 0.0, direction, pc.radius);
  while (rayQueryProceedEXT(query)) {
  }
  if (rayQueryGetIntersectionTypeEXT(query, true) == gl_RayQueryCommittedIntersectionNoneEXT) return 0.0;
  return kDistanceBased ? 1.0 - rayQueryGetIntersectionTEXT(query, true) / pc.radius : 1.0;
}
