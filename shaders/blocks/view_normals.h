#ifndef AOR_VIEW_NORMALS_H
#define AOR_VIEW_NORMALS_H
// The shared front's view-space normals from a capture's world-space ones: rotated by the view
// matrix and normalised; an unusable normal (NaN, Inf, zero) faces the camera, as GTAO treats it.
#include "../common/common.h"
#include "../common/shared_begin.h"

struct ViewNormalsConstants {
  vec4 worldToView0;  // columns of the world->view rotation
  vec4 worldToView1;
  vec4 worldToView2;
  ivec2 size;
};

AOR_FUNC vec3 viewSpaceNormal(vec3 world, vec3 c0, vec3 c1, vec3 c2) {
  vec3 n = c0 * world.x + c1 * world.y + c2 * world.z;
  float len2 = dot(n, n);
  if (!(len2 > 1e-12f) || isinf(len2)) return vec3(0.0f, 0.0f, 1.0f);
  return n * inversesqrt(len2);
}

#include "../common/shared_end.h"
#endif
