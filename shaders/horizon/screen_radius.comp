#version 450
// XeGTAO's screen-space radius per pixel (the main pass's `screenspaceRadius`, pixels), for
// --debug screen_radius only: the main pass keeps it in a register.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "horizon.h"

layout(local_size_x = kHorizonWorkgroupSize, local_size_y = kHorizonWorkgroupSize) in;
layout(constant_id = kHorizonSpecDepth32) const bool kDepth32 = false;
layout(push_constant, scalar) uniform Push { HorizonConstants pc; };
layout(set = 0, binding = 0) uniform sampler2D depthMips;
layout(set = 0, binding = 1) uniform writeonly image2D screenRadius;  // R32F

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= pc.viewportSize.x || pixel.y >= pc.viewportSize.y) return;
  float viewZ = texelFetch(depthMips, pixel, 0).x * (kDepth32 ? kHorizonDepth32PullIn : kHorizonDepth16PullIn);
  float radius = pc.effectRadius * pc.radiusMultiplier / (viewZ * pc.ndcToViewMulXPixelSize.x);
  imageStore(screenRadius, pixel, vec4(radius));
}
