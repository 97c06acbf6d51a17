#version 450
// Counts sky pixels and all pixels into a storage buffer with atomics.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "test_graph.h"
layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { TestGraphConstants pc; };
layout(set = 0, binding = 0, r32f) uniform readonly image2D distance;
layout(set = 0, binding = 1, std430) buffer Counter { uint sky; uint all; } counter;
void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= pc.size.x || p.y >= pc.size.y) return;
  if (imageLoad(distance, p).r <= 0.0) atomicAdd(counter.sky, 1u);
  atomicAdd(counter.all, 1u);
}
