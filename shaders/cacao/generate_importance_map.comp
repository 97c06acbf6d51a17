#version 450
// CACAO importance map (highest): FFX_CACAO_GenerateImportanceMap. Each texel covers 2x2 base-pass
// texels of all four layers (4x4 full-resolution pixels native): the spread between the least and
// most occluded of the 16 after the generate pass's strength and power, pow(2 x spread, 0.8).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "cacao_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 1) uniform sampler2DArray baseSsao;  // RG8: obscurance, weight
layout(set = 0, binding = 2, r8) uniform writeonly image2D importanceOut;

void main() {
  CacaoConstants c = cacaoLayers[0];
  ivec2 tid = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(vec2(tid), c.importanceMapDimensions))) return;
  // The 2x2 block of each layer in one gather at its shared corner (as FidelityFX's GatherRed, but
  // at the corner rather than a texel centre, so rounding cannot move the footprint), clamped.
  vec2 uv = vec2(2 * tid + 1) / vec2(textureSize(baseSsao, 0).xy);
  float minV = 1.0, maxV = 0.0;
  for (int layer = 0; layer < kCacaoLayers; ++layer) {
    vec4 vals = textureGather(baseSsao, vec3(uv, float(layer)));
    for (int i = 0; i < 4; ++i) {
      float v = c.effectShadowStrength * vals[i];
      v = pow(cacaoSaturate(1.0 - v), c.effectShadowPow);
      maxV = max(maxV, v);
      minV = min(minV, v);
    }
  }
  imageStore(importanceOut, tid, vec4(pow(cacaoSaturate((maxV - minV) * 2.0), 0.8)));
}
