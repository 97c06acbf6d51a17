#version 450
// The texture path's rate (bench/device_rates.cpp): one invocation per pixel, kFetchRateTaps
// texelFetch of an R32F image, summed and stored once so that none is dropped.
// kSpread 0: the taps cover an 8x8 neighbourhood of the pixel (cache-resident after the first
// touch): the fastest the path goes, which the floor uses. kSpread > 0: the taps lie along
// directions that turn per pixel and per tap, out to kSpread pixels, as a horizon search's do
// (a per-pixel noise angle, steps along slices): what fetches cost when neighbouring invocations
// do not share cache lines; reported beside the floor, never in it.
#extension GL_GOOGLE_include_directive : require
#include "fetch_rate.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const int kSpread = 0;
layout(push_constant) uniform Push { FetchRateConstants pc; };
layout(set = 0, binding = 0) uniform sampler2D source;
layout(set = 0, binding = 1, r32f) uniform writeonly image2D target;

// The source is the grid plus kFetchRatePad texels right and below: the neighbourhood needs no clamp.
ivec2 neighbourhoodTap(int tap) { return ivec2(tap & 7, (tap >> 3) & 7); }

// Tap k at distance spread x (k + 1) / taps, its angle the pixel's noise plus k golden angles.
ivec2 scatteredTap(ivec2 pixel, int tap) {
  uint h = uint(pixel.x) * 0x8da6b343u ^ uint(pixel.y) * 0xd8163841u;
  h = (h ^ (h >> 15)) * 0x2c1b3c6du;
  float angle = float(h >> 8) * (6.2831853 / 16777216.0) + float(tap) * 2.3999632;
  float distance = float(kSpread) * float(tap + 1) / float(kFetchRateTaps);
  return ivec2(round(vec2(cos(angle), sin(angle)) * distance));
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= pc.size.x || pixel.y >= pc.size.y) return;
  float sum = 0.0f;
  if (kSpread == 0) {
    for (int tap = 0; tap < kFetchRateTaps; ++tap) sum += texelFetch(source, pixel + neighbourhoodTap(tap), 0).r;
  } else {
    for (int tap = 0; tap < kFetchRateTaps; ++tap)
      sum += texelFetch(source, clamp(pixel + scatteredTap(pixel, tap), ivec2(0), pc.size - 1), 0).r;
  }
  imageStore(target, pixel, vec4(sum));
}
