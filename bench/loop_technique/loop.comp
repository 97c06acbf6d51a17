#version 450
#include "aoreplay.glsl"
// A known amount of work for counted-cost experiments (bench/ab_experiments.sh, kind `loop`):
// `iterations` dependent arithmetic steps per pixel, so 101 against 100 is 1 % more of the loop.
// The result depends on every step, so the compiler cannot drop any.

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(vec2(pixel), frame.size))) return;
  float x = texelFetch(in_linear_depth, pixel, 0).r;
  for (int i = 0; i < params.iterations; ++i) x = fract(x * 1.6180339 + 0.1234567);
  imageStore(out_ao, pixel, vec4(clamp(x, 0.0, 1.0)));
}
