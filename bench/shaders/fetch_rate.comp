#version 450
// The texture path's rate (bench/device_rates.cpp): one invocation per pixel, kFetchRateTaps
// texelFetch of an R32F image in an 8x8 neighbourhood of its pixel (cache-resident after the first
// touch), summed and stored once so that none is dropped.
#extension GL_GOOGLE_include_directive : require
#include "fetch_rate.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant) uniform Push { FetchRateConstants pc; };
layout(set = 0, binding = 0) uniform sampler2D source;
layout(set = 0, binding = 1, r32f) uniform writeonly image2D target;

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= pc.size.x || pixel.y >= pc.size.y) return;
  float sum = 0.0f;
  for (int tap = 0; tap < kFetchRateTaps; ++tap) {
    ivec2 at = clamp(pixel + ivec2(tap & 7, (tap >> 3) & 7) - ivec2(4), ivec2(0), pc.size - 1);
    sum += texelFetch(source, at, 0).r;
  }
  imageStore(target, pixel, vec4(sum));
}
