// CACAO importance map blurs (highest): FFX_CACAO_PostprocessImportanceMapA (postprocess_importance_map_a.comp)
// and, with CACAO_PASS_B, ...B (postprocess_importance_map_b.comp), which also sums every ninth
// texel into the load counter (as 8-bit values; LoadCounterAvgDiv makes that the mean importance).
#include "cacao_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
#ifdef CACAO_PASS_B
const bool kPassB = true;
#else
const bool kPassB = false;
#endif
layout(set = 0, binding = 1) uniform sampler2D importanceIn;  // bilinear, clamped
layout(set = 0, binding = 2, r8) uniform writeonly image2D importanceOut;
#ifdef CACAO_PASS_B
layout(set = 0, binding = 3, std430) buffer LoadCounter { uint loadCounter; };
#endif

void main() {
  CacaoConstants c = cacaoLayers[0];
  uvec2 tid = gl_GlobalInvocationID.xy;
  vec2 uv = (vec2(tid) + 0.5) * c.importanceMapInverseDimensions;
  float centre = textureLod(importanceIn, uv, 0.0).x;
  vec2 h = 0.5 * c.importanceMapInverseDimensions;
  vec4 vals;
  if (!kPassB) {
    vals.x = textureLod(importanceIn, uv + vec2(-h.x * 3.0, -h.y), 0.0).x;
    vals.y = textureLod(importanceIn, uv + vec2(+h.x, -h.y * 3.0), 0.0).x;
    vals.z = textureLod(importanceIn, uv + vec2(+h.x * 3.0, +h.y), 0.0).x;
    vals.w = textureLod(importanceIn, uv + vec2(-h.x, +h.y * 3.0), 0.0).x;
  } else {
    vals.x = textureLod(importanceIn, uv + vec2(-h.x, -h.y * 3.0), 0.0).x;
    vals.y = textureLod(importanceIn, uv + vec2(+h.x * 3.0, -h.y), 0.0).x;
    vals.z = textureLod(importanceIn, uv + vec2(+h.x, +h.y * 3.0), 0.0).x;
    vals.w = textureLod(importanceIn, uv + vec2(-h.x * 3.0, +h.y), 0.0).x;
  }
  float avgVal = dot(vals, vec4(0.25));
  vals.xy = max(vals.xy, vals.zw);
  float maxVal = max(centre, max(vals.x, vals.y));
  // lerp(maxVal, avgVal, c_FFX_CACAO_SmoothenImportance = 1) as HLSL evaluates it.
  float value = maxVal + 1.0 * (avgVal - maxVal);
  if (all(lessThan(vec2(tid), c.importanceMapDimensions))) imageStore(importanceOut, ivec2(tid), vec4(value));
  // Every thread of the dispatch adds, those past the edge with clamped samples, as FidelityFX's.
#ifdef CACAO_PASS_B
  if ((tid.x % 3u) + (tid.y % 3u) == 0u) atomicAdd(loadCounter, uint(cacaoSaturate(value) * 255.0 + 0.5));
#endif
}
