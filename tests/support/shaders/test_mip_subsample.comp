#version 450
// Levels 1-4 in one dispatch, one storage binding per level (as XeGTAO's prefilter writes its
// chain): texel t of level k is level 0's texel 2^k t. A thread per level-1 texel writes level k
// where its texel is a multiple of 2^(k-1).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "test_graph.h"
layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { TestGraphConstants pc; };  // size: level 1's
layout(set = 0, binding = 0, r32f) uniform readonly image2D level0;
layout(set = 0, binding = 1, r32f) uniform writeonly image2D level1;
layout(set = 0, binding = 2, r32f) uniform writeonly image2D level2;
layout(set = 0, binding = 3, r32f) uniform writeonly image2D level3;
layout(set = 0, binding = 4, r32f) uniform writeonly image2D level4;
void main() {
  ivec2 t = ivec2(gl_GlobalInvocationID.xy);
  if (t.x >= pc.size.x || t.y >= pc.size.y) return;
  vec4 v = imageLoad(level0, 2 * t);
  imageStore(level1, t, v);
  if (t.x % 2 == 0 && t.y % 2 == 0 && all(lessThan(t / 2, imageSize(level2)))) imageStore(level2, t / 2, v);
  if (t.x % 4 == 0 && t.y % 4 == 0 && all(lessThan(t / 4, imageSize(level3)))) imageStore(level3, t / 4, v);
  if (t.x % 8 == 0 && t.y % 8 == 0 && all(lessThan(t / 8, imageSize(level4)))) imageStore(level4, t / 8, v);
}
