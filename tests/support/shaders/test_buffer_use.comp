#version 450
// Reads the counts as a uniform buffer: visibility = 1 - the sky's share of the image, everywhere.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "test_graph.h"
layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { TestGraphConstants pc; };
layout(set = 0, binding = 0, std140) uniform Counter { uint sky; uint all; } counter;
layout(set = 0, binding = 1, r16f) uniform writeonly image2D visibility;
void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= pc.size.x || p.y >= pc.size.y) return;
  imageStore(visibility, p, vec4(1.0 - float(counter.sky) / float(max(counter.all, 1u))));
}
