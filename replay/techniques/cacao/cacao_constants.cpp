// CACAO's settings read from a run's Settings, its buffer sizes and its derived constants, as
// ffx_cacao.cpp's FFX_CACAO_UpdateBufferSizeInfo, FFX_CACAO_UpdateConstants and
// FFX_CACAO_UpdatePerPassConstants compute them (README.md here lists each with its source line).
#include <algorithm>
#include <cmath>

#include "shared_passes/camera.h"
#include "techniques/cacao/cacao_settings.h"

namespace aor {
namespace {

glm::vec2 inverse(glm::uvec2 size) { return {1.0f / float(size.x), 1.0f / float(size.y)}; }

// FFX_CACAO_UpdatePerPassConstants' rotation and scale of the pattern: five per layer, the
// sub-passes taken in the order spmap gives.
void setPatternRotScale(shader::CacaoConstants& c, int pass) {
  constexpr int kSubPasses = 5;
  constexpr int kSpmap[kSubPasses] = {0, 1, 4, 3, 2};
  for (int subPass = 0; subPass < kSubPasses; ++subPass) {
    float a = float(pass), b = float(kSpmap[subPass]);
    float angle0 = (a + b / float(kSubPasses)) * 3.1415926535897932384626433832795f * 0.5f;
    float ca = std::cos(angle0), sa = std::sin(angle0);
    float scale = 1.0f + (a - 1.5f + (b - (float(kSubPasses) - 1.0f) * 0.5f) / float(kSubPasses)) * 0.07f;
    c.patternRotScaleMatrices[subPass] = {scale * ca, scale * -sa, -scale * sa, -scale * ca};
  }
}

}  // namespace

bool cacaoGeneratesNormals(const CacaoSettings& settings, const CaptureLayout& capture) {
  return settings.generateNormals || !capture.normals;
}

CacaoBufferSizes cacaoBufferSizes(glm::uvec2 size, bool downsample) {
  glm::uvec2 half = (size + 1u) / 2u, quarter = (half + 1u) / 2u, eighth = (quarter + 1u) / 2u;
  CacaoBufferSizes s;
  s.inputOutput = size;
  s.ssao = downsample ? quarter : half;
  s.deinterleavedDepth = s.ssao;
  s.importanceMap = downsample ? eighth : quarter;
  return s;
}

std::array<shader::CacaoConstants, shader::kCacaoLayers> cacaoConstants(const FrameCamera& camera,
                                                                        const CacaoSettings& settings) {
  CacaoBufferSizes sizes = cacaoBufferSizes({uint32_t(camera.width), uint32_t(camera.height)}, settings.downsample);
  auto params = projectionParams(camera.projection, camera.width, camera.height);
  shader::CacaoConstants c{};

  c.bilateralSigmaSquared = settings.bilateralSigmaSquared;
  c.bilateralSimilarityDistanceSigma = settings.bilateralSimilarityDistanceSigma;
  // 9: PostprocessImportanceMapB adds every ninth texel only.
  c.loadCounterAvgDiv = 9.0f / float(double(sizes.importanceMap.x * sizes.importanceMap.y) * 255.0);

  ForwardViewCamera forward = forwardViewCamera(params);  // CACAO's view space and uv
  c.depthUnpackConsts = forward.depthUnpack;
  c.cameraTanHalfFov = forward.tanHalfFov;
  glm::vec2 signs = forward.axisSigns;
  c.ndcToViewMul = forward.ndcToViewMul;
  c.ndcToViewAdd = forward.ndcToViewAdd;
  // The depth buffer is the output's size (ratio 1, no border).
  c.depthBufferUvToViewMul = c.ndcToViewMul;
  c.depthBufferUvToViewAdd = c.ndcToViewAdd;

  c.effectRadius = std::clamp(settings.radius, 0.0f, 100000.0f);
  c.effectShadowStrength = std::clamp(settings.shadowMultiplier * 4.3f, 0.0f, 10.0f);
  c.effectShadowPow = std::clamp(settings.shadowPower, 0.0f, 10.0f);
  c.effectShadowClamp = std::clamp(settings.shadowClamp, 0.0f, 1.0f);
  c.effectFadeOutMul = -1.0f / (settings.fadeOutTo - settings.fadeOutFrom);
  c.effectFadeOutAdd = settings.fadeOutFrom / (settings.fadeOutTo - settings.fadeOutFrom) + 1.0f;
  c.effectHorizonAngleThreshold = std::clamp(settings.horizonAngleThreshold, 0.0f, 1.0f);
  float nearLimit = settings.radius * 1.2f;
  c.depthPrecisionOffsetMod = 0.9992f;
  if (settings.quality <= CacaoQuality::Low) {  // "nerf the effect a tiny bit"
    nearLimit *= 1.5f;
    if (settings.quality == CacaoQuality::Lowest) c.effectRadius *= 0.8f;
  }
  nearLimit /= c.cameraTanHalfFov.y;  // the same effect whatever the FOV
  c.effectSamplingRadiusNearLimitRec = 1.0f / nearLimit;
  c.adaptiveSampleCountLimit = settings.adaptiveQualityLimit;
  c.negRecEffectRadius = -1.0f / c.effectRadius;
  c.invSharpness = std::clamp(1.0f - settings.sharpness, 0.0f, 1.0f);
  c.detailAoStrength = settings.detailShadowStrength;

  c.ssaoBufferDimensions = glm::vec2(sizes.ssao);
  c.ssaoBufferInverseDimensions = inverse(sizes.ssao);
  c.depthBufferDimensions = glm::vec2(sizes.inputOutput);
  c.depthBufferInverseDimensions = inverse(sizes.inputOutput);
  c.depthBufferOffset = {0, 0};
  c.outputBufferDimensions = glm::vec2(sizes.inputOutput);
  c.outputBufferInverseDimensions = inverse(sizes.inputOutput);
  c.importanceMapDimensions = glm::vec2(sizes.importanceMap);
  c.importanceMapInverseDimensions = inverse(sizes.importanceMap);
  c.deinterleavedDepthBufferDimensions = glm::vec2(sizes.deinterleavedDepth);
  c.deinterleavedDepthBufferInverseDimensions = inverse(sizes.deinterleavedDepth);
  c.deinterleavedDepthBufferOffset = {0.0f, 0.0f};
  c.deinterleavedDepthBufferNormalisedOffset = {0.0f, 0.0f};

  // The capture's normals are RGBA16F floats (FidelityFX's 2, -1 unpack a UNORM G-buffer). They
  // are world space: the view rotation, then CACAO's axis flips (z forward). With generate_normals
  // FidelityFX sets the identity (its normals are made in view space), which prepare_normals never reads.
  c.normalsUnpackMul = 1.0f;
  c.normalsUnpackAdd = 0.0f;
  glm::mat3 flips(glm::vec3(signs.x, 0.0f, 0.0f), glm::vec3(0.0f, signs.y, 0.0f), glm::vec3(0.0f, 0.0f, -1.0f));
  c.normalsWorldToViewspaceMatrix = glm::mat4(flips * glm::mat3(camera.view));

  std::array<shader::CacaoConstants, shader::kCacaoLayers> layers{};
  for (int pass = 0; pass < shader::kCacaoLayers; ++pass) {
    layers[pass] = c;
    layers[pass].perPassFullResUvOffset = {float(pass % 2) / float(sizes.ssao.x), float(pass / 2) / float(sizes.ssao.y)};
    layers[pass].passIndex = pass;
    setPatternRotScale(layers[pass], pass);
  }
  return layers;
}

std::string cacaoPrepareDepthsPassName(const CacaoSettings& s) {
  std::string name = s.downsample ? "cacao_prepare_downsampled_depths" : "cacao_prepare_native_depths";
  if (s.quality == CacaoQuality::Lowest) return name + "_half";
  if (s.quality == CacaoQuality::Low) return name;
  return name + "_and_mips";
}

std::string cacaoPrepareNormalsPassName(const CacaoSettings& s, bool generateNormals) {
  std::string name = s.downsample ? "cacao_prepare_downsampled_normals" : "cacao_prepare_native_normals";
  return generateNormals ? name : name + "_from_input_normals";
}

std::string cacaoGeneratePassName(const CacaoSettings& s) { return "cacao_generate_q" + std::to_string(cacaoShaderQuality(s.quality)); }

std::string cacaoReinterleavePassName(const CacaoSettings& s) {
  if (s.downsample) {
    if (s.quality == CacaoQuality::Lowest) return "cacao_upscale_bilateral_5x5_half";
    if (s.quality <= CacaoQuality::Medium) return "cacao_upscale_bilateral_5x5_non_smart";
    return "cacao_upscale_bilateral_5x5_smart";
  }
  if (s.quality == CacaoQuality::Lowest) return "cacao_non_smart_half_apply";
  if (s.quality == CacaoQuality::Low) return "cacao_non_smart_apply";
  return "cacao_apply";
}

}  // namespace aor
