#ifndef AOR_CACAO_H
#define AOR_CACAO_H
// FidelityFX CACAO (seed 001) as a port: the constant buffer its passes share (FFX_CACAO_Constants,
// member for member), the sample pattern, the quality switches of ffx_cacao.hlsl, FidelityFX's
// defaults, and the per-tap math the C++ tests check; shared by the shaders and C++. What each
// value is and where it comes from in FidelityFX: replay/techniques/cacao/README.md.
#include "../common/shared_begin.h"

// Specialisation constant ids.
AOR_CONST int kCacaoSpecQuality = 0;       // generate: ffx_cacao.hlsl's qualityLevel 0..3 (Q0..Q3)
AOR_CONST int kCacaoSpecAdaptiveBase = 1;  // generate: FFX_CACAO_GenerateQ3Base (adaptiveBase)
AOR_CONST int kCacaoSpecDownsampled = 2;   // prepare passes: the Downsampled entry points
AOR_CONST int kCacaoSpecHalf = 3;          // prepare depths: the DepthsHalf entry points (layers 0 and 3)
AOR_CONST int kCacaoSpecBlurPasses = 4;    // edge-sensitive blur: FFX_CACAO_EdgeSensitiveBlurN's N
AOR_CONST int kCacaoSpecVariant = 5;       // apply / upscale / postprocess: which entry point (below)
AOR_CONST int kCacaoSpecLayerMask = 6;     // debug tiling: the layers written (bit k = layer k)
AOR_CONST int kCacaoSpecFirstChannel = 7;    // debug tiling: the channel moved first (the PNG shows the first)
AOR_CONST int kCacaoSpecDepthMipLevels = 8;  // prepare depths and mips: levels the image has (fewer than 4 on a tiny frame)
AOR_CONST int kCacaoSpecSmallLayer = 9;      // edge-sensitive blur: a layer under kCacaoMaxBlurPasses pixels a side (the periodic mirror)

// kCacaoSpecVariant of apply.comp and upscale_bilateral.comp.
AOR_CONST int kCacaoVariantSmart = 0;     // FFX_CACAO_Apply, FFX_CACAO_UpscaleBilateral5x5Smart
AOR_CONST int kCacaoVariantNonSmart = 1;  // FFX_CACAO_NonSmartApply, ..._UpscaleBilateral5x5NonSmart
AOR_CONST int kCacaoVariantHalf = 2;      // FFX_CACAO_NonSmartHalfApply, ..._UpscaleBilateral5x5Half

AOR_CONST int kCacaoLayers = 4;           // deinterleaved layers (2x2 pixel phases)
AOR_CONST uint kCacaoDepthMips = 4u;      // the prepare pass's MIP chain per layer (mip 0..3)
AOR_CONST int kCacaoMaxBlurPasses = 8;    // MAX_BLUR_PASSES
AOR_CONST uint kCacaoBlurWorkgroup = 16u; // FFX_CACAO_BLUR_WIDTH/HEIGHT
AOR_CONST int kCacaoBlurTileWidth = 4;    // FFX_CACAO_TILE_WIDTH: pixels per blur thread, across
AOR_CONST int kCacaoBlurTileHeight = 3;   // FFX_CACAO_TILE_HEIGHT: and down

// ffx_cacao.hlsl's taps and switches (qualityLevel: 0 Q0 .. 3 Q3/adaptive).
AOR_CONST int kCacaoMaxTaps = 32;            // FFX_CACAO_MAX_TAPS
AOR_CONST int kCacaoAdaptiveTapBaseCount = 5;  // FFX_CACAO_ADAPTIVE_TAP_BASE_COUNT
AOR_CONST int kCacaoAdaptiveTapFlexibleCount = kCacaoMaxTaps - kCacaoAdaptiveTapBaseCount;
AOR_CONST int kCacaoHaloingReductionAtQuality = 1;     // FFX_CACAO_HALOING_REDUCTION_ENABLE_AT_QUALITY_PRESET
AOR_CONST float kCacaoHaloingReductionAmount = 0.6f;   // FFX_CACAO_HALOING_REDUCTION_AMOUNT
AOR_CONST int kCacaoNormalBasedEdgesAtQuality = 2;     // FFX_CACAO_NORMAL_BASED_EDGES_ENABLE_AT_QUALITY_PRESET
AOR_CONST float kCacaoNormalBasedEdgesDotThreshold = 0.5f;
AOR_CONST int kCacaoDetailAoAtQuality = 1;             // FFX_CACAO_DETAIL_AO_ENABLE_AT_QUALITY_PRESET
AOR_CONST int kCacaoDepthMipsAtQuality = 2;            // FFX_CACAO_DEPTH_MIPS_ENABLE_AT_QUALITY_PRESET
AOR_CONST float kCacaoDepthMipsGlobalOffset = -4.3f;   // FFX_CACAO_DEPTH_MIPS_GLOBAL_OFFSET
AOR_CONST int kCacaoDepthBasedEdgesAtQuality = 1;      // FFX_CACAO_DEPTH_BASED_EDGES_ENABLE_AT_QUALITY_PRESET
AOR_CONST float kCacaoDetailRangeReduction = 4.0f;     // rangeReductionConst of the detail AO
// View depth stored for a surface at or beyond fp16's largest finite value, and for invalid depth
// (the R16F deinterleaved buffer would hold inf there): far beyond fade_out_to, so fully lit.
AOR_CONST float kCacaoMaxViewDepth = 65504.0f;

// FidelityFX's defaults (FFX_CACAO_DEFAULT_SETTINGS).
AOR_CONST float kCacaoDefaultRadius = 1.2f;
AOR_CONST float kCacaoDefaultShadowMultiplier = 1.0f;
AOR_CONST float kCacaoDefaultShadowPower = 1.5f;
AOR_CONST float kCacaoDefaultShadowClamp = 0.98f;
AOR_CONST float kCacaoDefaultHorizonAngleThreshold = 0.06f;
AOR_CONST float kCacaoDefaultFadeOutFrom = 50.0f;
AOR_CONST float kCacaoDefaultFadeOutTo = 300.0f;
AOR_CONST float kCacaoDefaultAdaptiveQualityLimit = 0.45f;
AOR_CONST int kCacaoDefaultBlurPassCount = 2;
AOR_CONST float kCacaoDefaultSharpness = 0.98f;
AOR_CONST float kCacaoDefaultDetailShadowStrength = 0.5f;
AOR_CONST float kCacaoDefaultBilateralSigmaSquared = 5.0f;
AOR_CONST float kCacaoDefaultBilateralSimilarityDistanceSigma = 0.01f;

// FFX_CACAO_Constants, member for member (scalar layout: the offsets of the C++ struct). One per
// deinterleaved layer ("pass"): PassIndex, PerPassFullResUVOffset and PatternRotScaleMatrices differ.
struct CacaoConstants {
  vec2 depthUnpackConsts;  // view z = x / (y - depth)
  vec2 cameraTanHalfFov;
  vec2 ndcToViewMul;  // CACAO's view space (x right, y up, z forward) from [0,1] uv
  vec2 ndcToViewAdd;
  vec2 depthBufferUvToViewMul;
  vec2 depthBufferUvToViewAdd;
  float effectRadius;
  float effectShadowStrength;
  float effectShadowPow;
  float effectShadowClamp;
  float effectFadeOutMul;
  float effectFadeOutAdd;
  float effectHorizonAngleThreshold;
  float effectSamplingRadiusNearLimitRec;
  float depthPrecisionOffsetMod;
  float negRecEffectRadius;
  float loadCounterAvgDiv;
  float adaptiveSampleCountLimit;
  float invSharpness;
  int passIndex;
  float bilateralSigmaSquared;
  float bilateralSimilarityDistanceSigma;
  vec4 patternRotScaleMatrices[5];
  float normalsUnpackMul;
  float normalsUnpackAdd;
  float detailAoStrength;
  float dummy0;
  vec2 ssaoBufferDimensions;
  vec2 ssaoBufferInverseDimensions;
  vec2 depthBufferDimensions;
  vec2 depthBufferInverseDimensions;
  ivec2 depthBufferOffset;
  vec2 perPassFullResUvOffset;
  vec2 outputBufferDimensions;
  vec2 outputBufferInverseDimensions;
  vec2 importanceMapDimensions;
  vec2 importanceMapInverseDimensions;
  vec2 deinterleavedDepthBufferDimensions;
  vec2 deinterleavedDepthBufferInverseDimensions;
  vec2 deinterleavedDepthBufferOffset;
  vec2 deinterleavedDepthBufferNormalisedOffset;
  mat4 normalsWorldToViewspaceMatrix;  // this tool's world normals to CACAO's view space (column-major)
};

// g_FFX_CACAO_samplePatternMain: per tap the offset (xy, unit disk), its weight (z) and
// log2(length(xy)) (w), which picks the depth MIP.
#define AOR_CACAO_SAMPLE_PATTERN                                                                           \
  0.78488064f, 0.56661671f, 1.500000f, -0.126083f, 0.26022232f, -0.29575172f, 1.500000f, -1.064030f,          \
      0.10459357f, 0.08372527f, 1.110000f, -2.730563f, -0.68286800f, 0.04963045f, 1.090000f, -0.498827f,      \
      -0.13570161f, -0.64190155f, 1.250000f, -0.532765f, -0.26193795f, -0.08205118f, 0.670000f, -1.783245f,   \
      -0.61177456f, 0.66664219f, 0.710000f, -0.044234f, 0.43675563f, 0.25119025f, 0.610000f, -1.167283f,      \
      0.07884444f, 0.86618668f, 0.640000f, -0.459002f, -0.12790935f, -0.29869005f, 0.600000f, -1.729424f,     \
      -0.04031125f, 0.02413622f, 0.600000f, -4.792042f, 0.16201244f, -0.52851415f, 0.790000f, -1.067055f,     \
      -0.70991218f, 0.47301072f, 0.640000f, -0.335236f, 0.03277707f, -0.22349690f, 0.600000f, -1.982384f,     \
      0.68921727f, 0.36800742f, 0.630000f, -0.266718f, 0.29251814f, 0.37775412f, 0.610000f, -1.422520f,       \
      -0.12224089f, 0.96582592f, 0.600000f, -0.426142f, 0.11071457f, -0.16131058f, 0.600000f, -2.165947f,     \
      0.46562141f, -0.59747696f, 0.600000f, -0.189760f, -0.51548797f, 0.11804193f, 0.600000f, -1.246800f,     \
      0.89141309f, -0.42090443f, 0.600000f, 0.028192f, -0.32402530f, -0.01591529f, 0.600000f, -1.543018f,     \
      0.60771245f, 0.41635221f, 0.600000f, -0.605411f, 0.02379565f, -0.08239821f, 0.600000f, -3.809046f,      \
      0.48951152f, -0.23657045f, 0.600000f, -1.189011f, -0.17611565f, -0.81696892f, 0.600000f, -0.513724f,    \
      -0.33930185f, -0.20732205f, 0.600000f, -1.698047f, -0.91974425f, 0.05403209f, 0.600000f, 0.062246f,     \
      -0.15064627f, -0.14949332f, 0.600000f, -1.896062f, 0.53180975f, -0.35210401f, 0.600000f, -0.758838f,    \
      0.41487166f, 0.81442589f, 0.600000f, -0.505648f, -0.24106961f, -0.32721516f, 0.600000f, -1.665244f

// g_FFX_CACAO_numTaps: taps (each two mirrored depth samples) of Q0, Q1, Q2; Q3 is adaptive.
AOR_FUNC int cacaoTapCount(int qualityLevel) { return qualityLevel == 0 ? 3 : (qualityLevel == 1 ? 5 : 12); }

AOR_FUNC float cacaoSaturate(float x) { return clamp(x, 0.0f, 1.0f); }

// FFX_CACAO_CalculatePixelObscurance: cos(normal, hit direction) above the horizon angle
// threshold, times the falloff 1 - |d|^2 / r^2.
AOR_FUNC float cacaoPixelObscurance(vec3 pixelNormal, vec3 hitDelta, float falloffCalcMulSq, float horizonAngleThreshold) {
  float lengthSq = dot(hitDelta, hitDelta);
  float nDotD = dot(pixelNormal, hitDelta) / sqrt(lengthSq);
  float falloffMult = max(0.0f, lengthSq * falloffCalcMulSq + 1.0f);
  return max(0.0f, nDotD - horizonAngleThreshold) * falloffMult;
}

// The haloing reduction weight (qualityLevel >= 1): samples far in front of the centre count less.
AOR_FUNC float cacaoHaloWeight(vec3 hitDelta, float negRecEffectRadius) {
  float reduct = max(0.0f, -hitDelta.z);
  reduct = cacaoSaturate(reduct * negRecEffectRadius + 2.0f);
  return kCacaoHaloingReductionAmount * reduct + (1.0f - kCacaoHaloingReductionAmount);
}

// FFX_CACAO_CalculateEdges: slope-sensitive depth edges, 1 = no edge.
AOR_FUNC vec4 cacaoCalculateEdges(float centerZ, float leftZ, float rightZ, float topZ, float bottomZ) {
  vec4 edgesLRTB = vec4(leftZ, rightZ, topZ, bottomZ) - vec4(centerZ);
  vec4 slopeAdjusted = edgesLRTB + vec4(edgesLRTB.y, edgesLRTB.x, edgesLRTB.w, edgesLRTB.z);
  edgesLRTB = min(abs(edgesLRTB), abs(slopeAdjusted));
  return clamp(vec4(1.3f) - edgesLRTB / (centerZ * 0.040f), vec4(0.0f), vec4(1.0f));
}

// FFX_CACAO_PackEdges: 2 bits a side (left in the top bits) as the unorm value R8 holds. HLSL's
// round takes halves to even, as roundEven does.
#ifdef __cplusplus
inline float cacaoRound(float x) { return float(std::nearbyint(x)); }
#else
float cacaoRound(float x) { return roundEven(x); }
#endif
AOR_FUNC float cacaoPackEdges(vec4 edgesLRTB) {
  vec4 q = clamp(edgesLRTB, vec4(0.0f), vec4(1.0f)) * 3.05f;
  q = vec4(cacaoRound(q.x), cacaoRound(q.y), cacaoRound(q.z), cacaoRound(q.w));
  return dot(q, vec4(64.0f / 255.0f, 16.0f / 255.0f, 4.0f / 255.0f, 1.0f / 255.0f));
}

// FFX_CACAO_UnpackEdges, with InvSharpness added (1 - sharpness: edges never fully stop the blur).
AOR_FUNC vec4 cacaoUnpackEdges(float packedValue, float invSharpness) {
  uint bits = uint(packedValue * 255.5f);
  vec4 edges = vec4(float((bits >> 6) & 3u), float((bits >> 4) & 3u), float((bits >> 2) & 3u), float(bits & 3u)) / 3.0f;
  return clamp(edges + vec4(invSharpness), vec4(0.0f), vec4(1.0f));
}

// FFX_CACAO_MipSmartAverage: the four depths averaged, each weighted down by its distance behind
// the nearest. FidelityFX writes -1 / r * r, which is -1 (the radius cancels); kept as written.
AOR_FUNC float cacaoMipSmartAverage(vec4 depths, float effectRadius) {
  float closest = min(min(depths.x, depths.y), min(depths.z, depths.w));
  float falloffCalcMulSq = -1.0f / effectRadius * effectRadius;
  vec4 dists = depths - vec4(closest);
  vec4 weights = clamp(dists * dists * falloffCalcMulSq + vec4(1.0f), vec4(0.0f), vec4(1.0f));
  return dot(weights, depths) / dot(weights, vec4(1.0f));
}

#include "../common/shared_end.h"
#endif
