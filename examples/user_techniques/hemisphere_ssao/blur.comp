#version 450
#include "aoreplay.glsl"
// A 5x5 blur of ao_raw that skips neighbours more than 5 % farther or nearer than the centre, so
// occlusion does not bleed across depth edges (with `blur` off, a copy).

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(vec2(pixel), frame.size))) return;
  float centre = texelFetch(in_ao_raw, pixel, 0).r;
  float dist = texelFetch(in_linear_depth, pixel, 0).r;
  if (params.blur == 0 || dist <= 0.0) {
    imageStore(out_ao, pixel, vec4(centre));
    return;
  }
  ivec2 last = ivec2(frame.size) - 1;
  float sum = 0.0, weight = 0.0;
  for (int y = -2; y <= 2; ++y)
    for (int x = -2; x <= 2; ++x) {
      ivec2 q = clamp(pixel + ivec2(x, y), ivec2(0), last);
      float d = texelFetch(in_linear_depth, q, 0).r;
      float w = (d > 0.0 && abs(d - dist) <= 0.05 * dist) ? 1.0 : 0.0;
      sum += w * texelFetch(in_ao_raw, q, 0).r;
      weight += w;
    }
  imageStore(out_ao, pixel, vec4(weight > 0.0 ? sum / weight : centre));
}
