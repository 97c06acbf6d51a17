#version 450
// Level 0 of the test chain: the front's linear distance, sky (-1) as 0.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "test_graph.h"
layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { TestGraphConstants pc; };
layout(set = 0, binding = 0, r32f) uniform readonly image2D distance;
layout(set = 0, binding = 1, r32f) uniform writeonly image2D level0;
void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= pc.size.x || p.y >= pc.size.y) return;
  imageStore(level0, p, vec4(max(imageLoad(distance, p).r, 0.0)));
}
