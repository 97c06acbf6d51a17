#version 450
// Reads every level of the chain through one sampler (texelFetch by level): visibility
// 1 / (1 + the sum over levels k of level k at pixel >> k).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "test_graph.h"
layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { TestGraphConstants pc; };
layout(set = 0, binding = 0) uniform sampler2D chain;  // every level
layout(set = 0, binding = 1, r16f) uniform writeonly image2D visibility;
void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= pc.size.x || p.y >= pc.size.y) return;
  float sum = 0.0;
  for (int k = 0; k <= pc.level; ++k) sum += texelFetch(chain, min(p >> k, textureSize(chain, k) - 1), k).r;
  imageStore(visibility, p, vec4(1.0 / (1.0 + sum)));
}
