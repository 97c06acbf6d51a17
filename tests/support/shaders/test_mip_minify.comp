#version 450
// Level k from level k - 1 through a sampler on that one level: the mean of each 2x2 block
// (edges clamped), summed in a fixed order so the CPU reproduces it exactly.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "test_graph.h"
layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { TestGraphConstants pc; };
layout(set = 0, binding = 0) uniform sampler2D finer;  // a view of level k - 1 only
layout(set = 0, binding = 1, r32f) uniform writeonly image2D coarser;
void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= pc.size.x || p.y >= pc.size.y) return;
  ivec2 last = textureSize(finer, 0) - 1;
  float a = texelFetch(finer, min(2 * p, last), 0).r, b = texelFetch(finer, min(2 * p + ivec2(1, 0), last), 0).r;
  float c = texelFetch(finer, min(2 * p + ivec2(0, 1), last), 0).r, d = texelFetch(finer, min(2 * p + 1, last), 0).r;
  imageStore(coarser, p, vec4(((a + b) + (c + d)) * 0.25));
}
