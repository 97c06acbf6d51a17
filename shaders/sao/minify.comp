#version 450
// One level of the CSZ pyramid from the one above by rotated-grid subsampling (no averaging: an
// average of two surfaces' depths is a depth neither has). Both channels (both layers) travel
// together, so a texel's two layers stay those of one pixel.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "sao.h"

layout(local_size_x = kWorkgroupSize, local_size_y = kWorkgroupSize) in;
layout(push_constant, scalar) uniform Push { SaoMinifyConstants pc; };
layout(set = 0, binding = 0) uniform sampler2D source;            // level m (any CSZ format)
layout(set = 0, binding = 1) uniform writeonly image2D destination;  // level m + 1

void main() {
  ivec2 t = ivec2(gl_GlobalInvocationID.xy);
  if (t.x >= pc.size.x || t.y >= pc.size.y) return;
  imageStore(destination, t, texelFetch(source, saoRotatedGridSource(t, pc.sourceSize), 0));
}
