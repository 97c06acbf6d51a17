#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "linearize_depth.h"

layout(local_size_x = kLinearizeWorkgroupSize, local_size_y = kLinearizeWorkgroupSize) in;
layout(push_constant, scalar) uniform Push { LinearizeConstants pc; };
layout(set = 0, binding = 0, r32f) uniform readonly image2D depthIn;  // depth-attachment values (storage read: cheaper than a sampler on lavapipe)
layout(set = 0, binding = 1, r32f) uniform writeonly image2D distanceOut;

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= pc.size.x || pixel.y >= pc.size.y) return;
  float depth = imageLoad(depthIn, pixel).r;
  imageStore(distanceOut, pixel, vec4(linearViewDistance(depth, pc.projection22, pc.projection32, pc.reversedDepth != 0u)));
}
