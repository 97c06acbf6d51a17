// CACAO's SSAO generation (FFX_CACAO_GenerateSSAOShadowsInternal) for one pixel of one
// deinterleaved layer; built as generate.comp (FFX_CACAO_GenerateQ0/Q1/Q2 and the adaptive base
// FFX_CACAO_GenerateQ3Base) and generate_adaptive.comp (CACAO_ADAPTIVE: FFX_CACAO_GenerateQ3, the
// base pass's result plus importance-driven extra taps). qualityLevel is ffx_cacao.hlsl's 0..3.
// The tilt of the mirrored taps and the border radius reduction are off at every level in
// FidelityFX (enabled at 99) and are left out.
#include "cacao_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = kCacaoSpecQuality) const int kQuality = 2;
layout(constant_id = kCacaoSpecAdaptiveBase) const bool kAdaptiveBase = false;
layout(constant_id = kCacaoSpecHalf) const bool kTwoLayers = false;

layout(set = 0, binding = 1) uniform sampler2DArray viewDepths;  // R16F, MIPs from medium; nearest, clamped
layout(set = 0, binding = 2) uniform sampler2DArray normals;     // RGBA8_SNORM, read with texelFetch
#ifdef CACAO_ADAPTIVE
layout(set = 0, binding = 3, std430) readonly buffer LoadCounter { uint loadCounter; };
layout(set = 0, binding = 4) uniform sampler2D importanceMap;    // R8, bilinear
layout(set = 0, binding = 5) uniform sampler2DArray baseSsao;    // RG8: the base pass's obscurance, weight / 20
layout(set = 0, binding = 6, rg8) uniform writeonly image2DArray ssaoOut;
#ifdef CACAO_COUNT_TAPS
// --debug adaptive_taps: extra taps and pixels where the importance map is >= 0.5, then below.
layout(set = 0, binding = 7, std430) buffer AdaptiveTaps { uint adaptiveTaps[4]; };
#endif
#else
layout(set = 0, binding = 3, rg8) uniform writeonly image2DArray ssaoOut;  // RG8: visibility (or obscurance), packed edges
#endif

const float kPattern[kCacaoMaxTaps * 4] = float[kCacaoMaxTaps * 4](AOR_CACAO_SAMPLE_PATTERN);

vec4 patternTap(int i) { return vec4(kPattern[4 * i], kPattern[4 * i + 1], kPattern[4 * i + 2], kPattern[4 * i + 3]); }

// FFX_CACAO_SSAOGeneration_GetNormalPass: a Load, so outside the layer it reads zero. The centre
// is inside (main returns past the layer's size) and a neighbour can leave it on one side only, so
// the caller says whether p is inside with one comparison.
vec3 normalAt(ivec2 p, int layer, bool inside) { return inside ? texelFetch(normals, ivec3(p, layer), 0).xyz : vec3(0.0); }


struct Centre {
  vec3 position;  // pulled towards the camera by DepthPrecisionOffsetMod
  vec3 normal;
  vec2 depthBufferUv;
  float falloffCalcMulSq;
  float mipOffset;
  vec2 rotScale0, rotScale1;  // the rows of FidelityFX's rotScale
};

// FFX_CACAO_SSAOTapInner: one depth sample's obscurance and weight.
void tapInner(CacaoConstants c, Centre p, int layer, vec2 uv, float mipLevel, float weightMod,
              inout float obscuranceSum, inout float weightSum) {
  float z = textureLod(viewDepths, vec3(uv, float(layer)), mipLevel).x;
  vec3 hitDelta = cacaoDepthBufferUvToView(c, uv, z) - p.position;
  float obscurance = cacaoPixelObscurance(p.normal, hitDelta, p.falloffCalcMulSq, c.effectHorizonAngleThreshold);
  float weight = kQuality >= kCacaoHaloingReductionAtQuality ? cacaoHaloWeight(hitDelta, c.negRecEffectRadius) : 1.0;
  weight *= weightMod;
  obscuranceSum += obscurance * weight;
  weightSum += weight;
}

// FFX_CACAO_SSAOTap: pattern tap i, rotated and scaled, snapped to a texel, and its mirror.
void tap(CacaoConstants c, Centre p, int layer, int i, inout float obscuranceSum, inout float weightSum) {
  vec4 s = patternTap(i);
  vec2 offset = roundEven(vec2(dot(p.rotScale0, s.xy), dot(p.rotScale1, s.xy)));
  float mipLevel = kQuality < kCacaoDepthMipsAtQuality ? 0.0 : s.w + p.mipOffset;
  vec2 inv = c.deinterleavedDepthBufferInverseDimensions;
  tapInner(c, p, layer, offset * inv + p.depthBufferUv, mipLevel, s.z, obscuranceSum, weightSum);
  tapInner(c, p, layer, -offset * inv + p.depthBufferUv, mipLevel, s.z, obscuranceSum, weightSum);
}

#ifdef CACAO_ADAPTIVE
// FFX_CACAO_SSAOGetSampleData + GetHits2 + AddHits: an adaptive tap. As FidelityFX's AddHits, the
// haloing weight replaces the pattern's weight instead of scaling it.
void adaptiveTap(CacaoConstants c, Centre p, int layer, int i, inout float obscuranceSum, inout float weightSum) {
  vec4 s = patternTap(i);
  vec2 uvOffset = roundEven(vec2(dot(p.rotScale0, s.xy), dot(p.rotScale1, s.xy))) * c.deinterleavedDepthBufferInverseDimensions;
  float mipLevel = s.w + p.mipOffset;
  float weight = s.z;
  for (int side = 0; side < 2; ++side) {
    vec2 uv = side == 0 ? p.depthBufferUv + uvOffset : p.depthBufferUv - uvOffset;
    float z = textureLod(viewDepths, vec3(uv, float(layer)), mipLevel).x;
    vec3 hitDelta = cacaoDepthBufferUvToView(c, uv, z) - p.position;
    float obscurance = cacaoPixelObscurance(p.normal, hitDelta, p.falloffCalcMulSq, c.effectHorizonAngleThreshold);
    weight = cacaoHaloWeight(hitDelta, c.negRecEffectRadius);
    obscuranceSum += obscurance * weight;
    weightSum += weight;
  }
}
#endif

void main() {
  int layer = cacaoLayerOf(gl_WorkGroupID.z, kTwoLayers);
  CacaoConstants c = cacaoLayers[layer];
  ivec2 coord = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(vec2(coord), c.ssaoBufferDimensions))) return;
  vec2 svPos = vec2(coord);

  Centre p;
  p.depthBufferUv = (svPos + 0.5) * c.deinterleavedDepthBufferInverseDimensions + c.deinterleavedDepthBufferNormalisedOffset;
  // The centre and its four neighbours, clamped, from two gathers as FidelityFX's two GatherReds,
  // taken at the corners of the 2x2 blocks (up-left and down-right of the centre) instead of at
  // the centre texel's middle, so rounding cannot move the footprints. x, y, z, w are texels
  // (0, 1), (1, 1), (1, 0), (0, 0) of a footprint.
  // The corners by the constants' inverse size (no textureSize query, a texture-unit instruction on
  // NVIDIA, and no divides); at a corner the last bits cannot move the footprint.
  vec2 depthInv = c.deinterleavedDepthBufferInverseDimensions;
  vec4 valuesUL = textureGather(viewDepths, vec3(vec2(coord) * depthInv, float(layer)));
  vec4 valuesBR = textureGather(viewDepths, vec3(vec2(coord + 1) * depthInv, float(layer)));
  float pixZ = valuesUL.y;
  float pixLZ = valuesUL.x, pixRZ = valuesBR.z;
  float pixTZ = valuesUL.z, pixBZ = valuesBR.x;

  vec2 normalizedScreenPos = (svPos + 0.5) * c.ssaoBufferInverseDimensions;
  p.position = cacaoNdcToView(c, normalizedScreenPos, pixZ);
  p.normal = normalAt(coord, layer, true);
  vec2 pixelDirRBViewspaceSizeAtCenterZ = p.position.z * c.ndcToViewMul * c.ssaoBufferInverseDimensions;

  // FFX_CACAO_CalculateRadiusParameters.
  float effectRadius = c.effectRadius;
  float tooCloseLimitMod = cacaoSaturate(length(p.position) * c.effectSamplingRadiusNearLimitRec) * 0.8 + 0.2;
  effectRadius *= tooCloseLimitMod;
  float pixLookupRadiusMod = (0.85 * effectRadius) / pixelDirRBViewspaceSizeAtCenterZ.x;
  p.falloffCalcMulSq = -1.0 / (effectRadius * effectRadius);

  // The layer's rotation and scale of the pattern, one of five by pixel.
  uint pseudoRandomIndex = uint(svPos.y * 2.0 + svPos.x) % 5u;
  // Straight from the uniform buffer: a dynamic index into the local copy c can keep the whole copy
  // (376 bytes) in local memory.
  vec4 rs = cacaoLayers[layer].patternRotScaleMatrices[pseudoRandomIndex];
  p.rotScale0 = vec2(rs.x * pixLookupRadiusMod, rs.y * pixLookupRadiusMod);
  p.rotScale1 = vec2(rs.z * pixLookupRadiusMod, rs.w * pixLookupRadiusMod);

  float obscuranceSum = 0.0, weightSum = 0.0;
  vec4 edgesLRTB = vec4(1.0);
  p.position *= c.depthPrecisionOffsetMod;

  if (!kAdaptiveBase && kQuality >= kCacaoDepthBasedEdgesAtQuality) edgesLRTB = cacaoCalculateEdges(pixZ, pixLZ, pixRZ, pixTZ, pixBZ);

  // Detail AO from the four neighbours the edges used.
  if (!kAdaptiveBase && kQuality >= kCacaoDetailAoAtQuality) {
    vec3 dirZNormalized = vec3(p.position.xy / p.position.zz, 1.0);
    vec3 pixLDelta = vec3(-pixelDirRBViewspaceSizeAtCenterZ.x, 0.0, 0.0) + dirZNormalized * (pixLZ - p.position.z);
    vec3 pixRDelta = vec3(+pixelDirRBViewspaceSizeAtCenterZ.x, 0.0, 0.0) + dirZNormalized * (pixRZ - p.position.z);
    vec3 pixTDelta = vec3(0.0, -pixelDirRBViewspaceSizeAtCenterZ.y, 0.0) + dirZNormalized * (pixTZ - p.position.z);
    vec3 pixBDelta = vec3(0.0, +pixelDirRBViewspaceSizeAtCenterZ.y, 0.0) + dirZNormalized * (pixBZ - p.position.z);
    float modifiedFalloffCalcMulSq = kCacaoDetailRangeReduction * p.falloffCalcMulSq;
    vec4 additional;
    additional.x = cacaoPixelObscurance(p.normal, pixLDelta, modifiedFalloffCalcMulSq, c.effectHorizonAngleThreshold);
    additional.y = cacaoPixelObscurance(p.normal, pixRDelta, modifiedFalloffCalcMulSq, c.effectHorizonAngleThreshold);
    additional.z = cacaoPixelObscurance(p.normal, pixTDelta, modifiedFalloffCalcMulSq, c.effectHorizonAngleThreshold);
    additional.w = cacaoPixelObscurance(p.normal, pixBDelta, modifiedFalloffCalcMulSq, c.effectHorizonAngleThreshold);
    obscuranceSum += c.detailAoStrength * dot(additional, edgesLRTB);
  }

  // Sharp normals make edges too.
  if (!kAdaptiveBase && kQuality >= kCacaoNormalBasedEdgesAtQuality) {
    vec2 size = c.ssaoBufferDimensions;
    vec4 normalEdges;
    normalEdges.x = cacaoSaturate(dot(p.normal, normalAt(coord + ivec2(-1, 0), layer, coord.x > 0)) + kCacaoNormalBasedEdgesDotThreshold);
    normalEdges.y = cacaoSaturate(dot(p.normal, normalAt(coord + ivec2(+1, 0), layer, float(coord.x + 1) < size.x)) + kCacaoNormalBasedEdgesDotThreshold);
    normalEdges.z = cacaoSaturate(dot(p.normal, normalAt(coord + ivec2(0, -1), layer, coord.y > 0)) + kCacaoNormalBasedEdgesDotThreshold);
    normalEdges.w = cacaoSaturate(dot(p.normal, normalAt(coord + ivec2(0, +1), layer, float(coord.y + 1) < size.y)) + kCacaoNormalBasedEdgesDotThreshold);
    edgesLRTB *= normalEdges;
  }

  p.mipOffset = kQuality < kCacaoDepthMipsAtQuality ? 0.0 : log2(pixLookupRadiusMod) + kCacaoDepthMipsGlobalOffset;

#ifdef CACAO_ADAPTIVE
  vec2 fullResUv = normalizedScreenPos + c.perPassFullResUvOffset;
  float importance = textureLod(importanceMap, fullResUv, 0.0).x;
  float unlimitedImportance = importance;
  // Keeps the detail AO's share the same whatever the importance.
  obscuranceSum *= (float(kCacaoAdaptiveTapBaseCount) / float(kCacaoMaxTaps)) +
                   (importance * float(kCacaoAdaptiveTapFlexibleCount) / float(kCacaoMaxTaps));
  vec2 baseValues = texelFetch(baseSsao, ivec3(coord, layer), 0).xy;
  weightSum += baseValues.y * float(kCacaoAdaptiveTapBaseCount * 4.0);
  obscuranceSum += baseValues.x * weightSum;
  float avgTotalImportance = float(loadCounter) * c.loadCounterAvgDiv;
  float importanceLimiter = cacaoSaturate(c.adaptiveSampleCountLimit / avgTotalImportance);
  importance *= importanceLimiter;
  float additionalSampleCountFlt = float(kCacaoAdaptiveTapFlexibleCount) * importance + 1.5;
  uint additionalSamples = uint(additionalSampleCountFlt);
  int additionalSamplesTo = int(min(uint(kCacaoMaxTaps), additionalSamples + uint(kCacaoAdaptiveTapBaseCount)));
  // Unrolled to the most taps with an exit: every copy then indexes the pattern with a constant
  // (lavapipe keeps a loop with a dynamic bound rolled, and its dynamic pattern index costs x40).
  AOR_UNROLL for (int i = kCacaoAdaptiveTapBaseCount; i < kCacaoMaxTaps; ++i) {
    if (i >= additionalSamplesTo) break;
    adaptiveTap(c, p, layer, i, obscuranceSum, weightSum);
  }
#ifdef CACAO_COUNT_TAPS
  uint bucket = unlimitedImportance >= 0.5 ? 0u : 2u;
  atomicAdd(adaptiveTaps[bucket], uint(additionalSamplesTo - kCacaoAdaptiveTapBaseCount));
  atomicAdd(adaptiveTaps[bucket + 1u], 1u);
#endif
#else
  int taps = kAdaptiveBase ? kCacaoAdaptiveTapBaseCount : cacaoTapCount(kQuality);
  AOR_UNROLL for (int i = 0; i < taps; ++i) tap(c, p, layer, i, obscuranceSum, weightSum);
#endif

  float obscurance = obscuranceSum / weightSum;
  if (kAdaptiveBase) {
    // Untransformed obscurance and the weight, for the adaptive pass.
    imageStore(ssaoOut, ivec3(coord, layer), vec4(obscurance, weightSum / (float(kCacaoAdaptiveTapBaseCount) * 4.0), 0.0, 0.0));
    return;
  }

  // Fade out with distance, and where two opposite sides are edges.
  float fadeOut = cacaoSaturate(p.position.z * c.effectFadeOutMul + c.effectFadeOutAdd);
  if (kQuality >= kCacaoDepthBasedEdgesAtQuality) {
    float edgeFadeoutFactor = cacaoSaturate((1.0 - edgesLRTB.x - edgesLRTB.y) * 0.35) + cacaoSaturate((1.0 - edgesLRTB.z - edgesLRTB.w) * 0.35);
    fadeOut *= cacaoSaturate(1.0 - edgeFadeoutFactor);
  }
  obscurance = c.effectShadowStrength * obscurance;
  obscurance = min(obscurance, c.effectShadowClamp);
  obscurance *= fadeOut;
  float occlusion = pow(cacaoSaturate(1.0 - obscurance), c.effectShadowPow);
  float edges = cacaoPackEdges(kQuality == 0 ? vec4(1.0) : edgesLRTB);  // Q0 has no edges
  imageStore(ssaoOut, ivec3(coord, layer), vec4(occlusion, edges, 0.0, 0.0));
}
