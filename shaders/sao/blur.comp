#version 450
// One leg of SAO's separable depth-aware bilateral blur (run horizontally, then vertically):
// 2 radius + 1 taps `step` pixels apart, Gaussian weights times a depth-similarity weight on
// layer 0's camera-space Z, normalised. Sky is copied.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "sao.h"

layout(local_size_x = kWorkgroupSize, local_size_y = kWorkgroupSize) in;
layout(push_constant, scalar) uniform Push { SaoBlurConstants pc; };
layout(set = 0, binding = 0, r16f) uniform readonly image2D aoIn;
layout(set = 0, binding = 1) uniform sampler2D csz;  // level 0; R is layer 0
layout(set = 0, binding = 2) uniform writeonly image2D aoOut;

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= pc.size.x || pixel.y >= pc.size.y) return;
  float centre = imageLoad(aoIn, pixel).r;
  float z = texelFetch(csz, pixel, 0).r;
  if (z <= 0.0) {
    imageStore(aoOut, pixel, vec4(centre));
    return;
  }
  float sum = centre, weights = 1.0;
  for (int r = -pc.radius; r <= pc.radius; ++r) {
    if (r == 0) continue;
    ivec2 tap = pixel + pc.axis * (r * pc.step);
    if (any(lessThan(tap, ivec2(0))) || any(greaterThanEqual(tap, pc.size))) continue;
    float tapZ = texelFetch(csz, tap, 0).r;
    if (tapZ <= 0.0) continue;
    float w = saoBlurWeight(r, pc.sigma, tapZ - z, pc.edgeSharpness);
    sum += w * imageLoad(aoIn, tap).r;
    weights += w;
  }
  imageStore(aoOut, pixel, vec4(sum / weights));
}
