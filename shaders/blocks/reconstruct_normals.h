#ifndef AOR_RECONSTRUCT_NORMALS_H
#define AOR_RECONSTRUCT_NORMALS_H
// Normals from depth, for captures that carry none: cross product of the view-space differences
// toward the neighbours with the smaller depth jump, so silhouettes do not bend the normal.
#include "../common/common.h"
#include "../common/shared_begin.h"

struct ReconstructNormalsConstants {
  vec2 ndcToViewMul;
  vec2 ndcToViewAdd;
  vec2 invSize;
  ivec2 size;
};

// Picks the one-sided difference with the smaller depth change; `centre`, `prev`, `next` are view positions.
AOR_FUNC vec3 smallerDifference(vec3 centre, vec3 prev, vec3 next, bool hasPrev, bool hasNext) {
  if (!hasPrev) return next - centre;
  if (!hasNext) return centre - prev;
  return abs(next.z - centre.z) < abs(centre.z - prev.z) ? next - centre : centre - prev;
}

#include "../common/shared_end.h"
#endif
