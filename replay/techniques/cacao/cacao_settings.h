#pragma once
// FidelityFX CACAO (seed 001): a run's settings as FFX_CACAO_Settings holds them, the buffer sizes
// of FFX_CACAO_UpdateBufferSizeInfo, the constants of FFX_CACAO_UpdateConstants and
// FFX_CACAO_UpdatePerPassConstants (from this tool's camera), and which entry point each pass runs
// at each quality level (the seed's pass table). The keys are declared in cacao_technique.cpp.
#include <array>
#include <string>

#include "cacao/cacao.h"
#include "technique_api/frame_builder.h"
#include "technique_api/settings.h"

namespace aor {

// FFX_CACAO_Quality, in its order (the `quality` key's choice indices).
enum class CacaoQuality { Lowest = 0, Low = 1, Medium = 2, High = 3, Highest = 4 };

struct CacaoSettings {
  float radius = shader::kCacaoDefaultRadius;
  CacaoQuality quality = CacaoQuality::High;
  float shadowMultiplier = shader::kCacaoDefaultShadowMultiplier;
  float shadowPower = shader::kCacaoDefaultShadowPower;
  float shadowClamp = shader::kCacaoDefaultShadowClamp;
  float horizonAngleThreshold = shader::kCacaoDefaultHorizonAngleThreshold;
  float fadeOutFrom = shader::kCacaoDefaultFadeOutFrom;
  float fadeOutTo = shader::kCacaoDefaultFadeOutTo;
  float adaptiveQualityLimit = shader::kCacaoDefaultAdaptiveQualityLimit;
  int blurPassCount = shader::kCacaoDefaultBlurPassCount;
  float sharpness = shader::kCacaoDefaultSharpness;
  float detailShadowStrength = shader::kCacaoDefaultDetailShadowStrength;
  bool generateNormals = false;  // forced on where the capture has no normals (cacaoGeneratesNormals)
  float bilateralSigmaSquared = shader::kCacaoDefaultBilateralSigmaSquared;
  float bilateralSimilarityDistanceSigma = shader::kCacaoDefaultBilateralSimilarityDistanceSigma;
  bool downsample = false;
};

CacaoSettings cacaoSettings(const Settings& settings);
// generate_normals=1, or a capture without normals.
bool cacaoGeneratesNormals(const CacaoSettings& settings, const CaptureLayout& capture);

// ffx_cacao.hlsl's qualityLevel of the generate passes: lowest and low run Q0, medium Q1, high Q2,
// highest Q3 (adaptive).
inline int cacaoShaderQuality(CacaoQuality q) { return q == CacaoQuality::Lowest ? 0 : int(q) - 1; }
// Lowest keeps layers 0 and 3 only (the DepthsHalf entry points).
inline bool cacaoTwoLayers(CacaoQuality q) { return q == CacaoQuality::Lowest; }
inline bool cacaoAdaptive(CacaoQuality q) { return q == CacaoQuality::Highest; }
inline bool cacaoDepthMips(CacaoQuality q) { return q >= CacaoQuality::Medium; }

// FFX_CACAO_BufferSizeInfo (no depth buffer border: every offset is 0).
struct CacaoBufferSizes {
  glm::uvec2 inputOutput{0}, ssao{0}, deinterleavedDepth{0}, importanceMap{0};
};
CacaoBufferSizes cacaoBufferSizes(glm::uvec2 frameSize, bool downsample);

// FFX_CACAO_UpdateConstants + FFX_CACAO_UpdatePerPassConstants for each of the four layers.
// CACAO's view space is x right, y up, z forward: this tool's with z flipped (and x or y flipped
// where the capture's projection points them the other way).
std::array<shader::CacaoConstants, shader::kCacaoLayers> cacaoConstants(const FrameCamera& camera,
                                                                        const CacaoSettings& settings);

// The graph's pass names, one per entry point of the seed's table (README.md here).
std::string cacaoPrepareDepthsPassName(const CacaoSettings& settings);
std::string cacaoPrepareNormalsPassName(const CacaoSettings& settings, bool generateNormals);
std::string cacaoGeneratePassName(const CacaoSettings& settings);
std::string cacaoReinterleavePassName(const CacaoSettings& settings);  // the apply or the bilateral upsample

// The passes (cacao_passes.cpp), in the seed's order; addCacaoPasses returns the R8 output.
graph::ResourceId addCacaoPasses(FrameBuilder& frame, const CacaoSettings& settings);

}  // namespace aor
