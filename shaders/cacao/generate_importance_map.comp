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
  ivec2 last = textureSize(baseSsao, 0).xy - 1;
  float minV = 1.0, maxV = 0.0;
  for (int layer = 0; layer < kCacaoLayers; ++layer)
    for (int i = 0; i < 4; ++i) {
      ivec2 q = min(2 * tid + ivec2(i % 2, i / 2), last);  // the 2x2 a gather at the texel's corner reads, clamped
      float v = c.effectShadowStrength * texelFetch(baseSsao, ivec3(q, layer), 0).x;
      v = pow(cacaoSaturate(1.0 - v), c.effectShadowPow);
      maxV = max(maxV, v);
      minV = min(minV, v);
    }
  imageStore(importanceOut, tid, vec4(pow(cacaoSaturate((maxV - minV) * 2.0), 0.8)));
}
