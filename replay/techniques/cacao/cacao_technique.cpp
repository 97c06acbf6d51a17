// Seed 001: AMD's FidelityFX CACAO (an optimised Intel ASSAO) as a technique module: its settings
// under FFX_CACAO_Settings' names and defaults, its five quality levels as presets, native or
// downsampled SSAO buffer, its passes (cacao_passes.cpp) per the seed's table. Point by point: README.md here.
#include "techniques/cacao/cacao_settings.h"
#include "technique_api/key_table.h"
#include "techniques/registry.h"

namespace aor {
namespace {

void addCacaoPipeline(FrameBuilder& frame, const Settings& settings) {
  CacaoSettings c = cacaoSettings(settings);
  frame.setOutput(addCacaoPasses(frame, c), OutputLayout::visibilityOnly());
}

// Every key with its CacaoSettings field, under FFX_CACAO_Settings' names; defaults are the struct's.
const KeyTable<CacaoSettings>& keyTable() {
  using C = CacaoSettings;
  static const KeyTable<C> table = {
      radiusKey(&C::radius),
      enumKey(&C::quality, "quality", {"lowest", "low", "medium", "high", "highest"},
              "FFX_CACAO_Quality: which passes and entry points run (the seed's pass table)"),
      floatKey(&C::shadowMultiplier, "shadow_multiplier", 0.0, 5.0, "shadowMultiplier: EffectShadowStrength = 4.3 x this",
               kTunable),
      floatKey(&C::shadowPower, "shadow_power", 0.5, 5.0, "shadowPower: EffectShadowPow, the exponent on visibility", kTunable),
      floatKey(&C::shadowClamp, "shadow_clamp", 0.0, 1.0, "shadowClamp: EffectShadowClamp, the most obscurance kept", kTunable),
      floatKey(&C::horizonAngleThreshold, "horizon_angle_threshold", 0.0, 0.2,
               "horizonAngleThreshold: cosines below this occlude nothing (limits self-shadowing)", kTunable),
      floatKey(&C::fadeOutFrom, "fade_out_from", 0.0, 1e5, "fadeOutFrom: view distance where AO starts to fade"),
      floatKey(&C::fadeOutTo, "fade_out_to", 0.0, 1e5, "fadeOutTo: view distance where AO is gone"),
      floatKey(&C::adaptiveQualityLimit, "adaptive_quality_limit", 0.0, 1.0,
               "adaptiveQualityLimit: AdaptiveSampleCountLimit, the mean importance the extra taps may reach (highest)", kTunable),
      intKey(&C::blurPassCount, "blur_pass_count", 0, shader::kCacaoMaxBlurPasses,
             "blurPassCount: edge-sensitive 3x3 blur iterations, 0 = no blur pass"),
      floatKey(&C::sharpness, "sharpness", 0.0, 1.0, "sharpness: InvSharpness = 1 - this, how much edges stop the blur", kTunable),
      floatKey(&C::detailShadowStrength, "detail_shadow_strength", 0.0, 5.0,
               "detailShadowStrength: DetailAOStrength, AO from the four neighbours (medium and up)", kTunable),
      boolKey(&C::generateNormals, "generate_normals",
              "generateNormals: normals from depth derivatives (forced on a capture without normals)"),
      floatKey(&C::bilateralSigmaSquared, "bilateral_sigma_squared", 0.1, 100.0,
               "bilateralSigmaSquared: spatial width of the 5x5 upsample (downsample=1)"),
      floatKey(&C::bilateralSimilarityDistanceSigma, "bilateral_similarity_distance_sigma", 1e-4, 1.0,
               "bilateralSimilarityDistanceSigma: depth sharpness of the upsample (downsample=1)"),
      boolKey(&C::downsample, "downsample", "useDownsampledSsao: SSAO at quarter resolution, bilateral 5x5 upsample at the end"),
  };
  return table;
}

Technique makeCacao() {
  Technique t;
  t.name = "cacao";
  t.seed = "001 FidelityFX CACAO";
  t.summary = "AMD's FidelityFX CACAO (ASSAO): deinterleaved depth and normals, five quality levels, adaptive at highest, "
              "edge-sensitive blur";
  t.parameters = keyTable().parameters();
  for (int q = 0; q <= int(CacaoQuality::Highest); ++q)
    t.presets.push_back({t.parameters[1].choices[size_t(q)], {{"quality", double(q)}}});
  t.defaultPreset = "high";
  t.debugViews = {
      {"deinterleaved_depth", "prepare depths' MIP 0: view depth of the four 2x2 phases tiled 2x2 (lowest: layers 1, 2 empty)"},
      {"deinterleaved_normals", "prepare normals' output, CACAO's view space (x right, y up, z forward), layers tiled 2x2"},
      {"edges", "the generate pass's packed edges (2 bits a side, left in the top bits), layers tiled 2x2"},
      {"ssao_raw", "the generate pass's visibility per layer before the blur, tiled 2x2"},
      {"importance_map", "highest: the importance map after postprocess B (R8, one texel per 4x4 pixels native)"},
      {"adaptive_taps", "highest, report.json frames[i].debug.adaptive_taps: extra taps and pixels where importance >= 0.5, "
                        "then extra taps and pixels below"},
      {"ao", "the output: visibility after apply or the bilateral upsample (R8)"},
  };
  t.addPasses = addCacaoPipeline;
  return t;
}

}  // namespace

const Technique& cacaoTechnique() {
  static const Technique t = makeCacao();
  return t;
}

CacaoSettings cacaoSettings(const Settings& settings) { return keyTable().read(settings); }

}  // namespace aor
