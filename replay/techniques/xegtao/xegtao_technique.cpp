// Seed 002: Intel's XeGTAO (depth prefilter -> main pass -> edge-aware denoise), as a technique
// module: its settings under XeGTAO's names and defaults, its quality presets, its passes (in
// xegtao_passes.cpp), the shared temporal block as an option. Point by point: README.md here.
#include "shared_passes/shared_passes.h"
#include "technique_api/key_table.h"
#include "techniques/registry.h"
#include "techniques/xegtao/xegtao_settings.h"

namespace aor {
namespace {

// Every key with its XeGtaoSettings field, under XeGTAO's names; defaults are the struct's.
const KeyTable<XeGtaoSettings>& keyTable() {
  using X = XeGtaoSettings;
  static const KeyTable<X> table = {
      radiusKey(&X::radius),
      intKey(&X::slices, "slices", 1, 32, "slice directions per pixel (XeGTAO's sliceCount)"),
      intKey(&X::steps, "steps", 1, 32, "samples per side of a slice (stepsPerSlice)"),
      floatKey(&X::radiusMultiplier, "radius_multiplier", 0.3, 3.0, "RadiusMultiplier: the radius searched is radius x this",
               kTunable),
      floatKey(&X::falloffRange, "falloff_range", 0.0, 1.0, "FalloffRange: fraction of the radius over which samples fade out",
               kTunable),
      floatKey(&X::sampleDistributionPower, "sample_distribution_power", 1.0, 3.0,
               "SampleDistributionPower: step positions t^power, >1 crowds them towards the centre", kTunable),
      floatKey(&X::thinOccluderCompensation, "thin_occluder_compensation", 0.0, 0.7,
               "ThinOccluderCompensation: samples behind the centre fade sooner, 0 = off", kTunable),
      floatKey(&X::finalValuePower, "final_value_power", 0.5, 5.0, "FinalValuePower: exponent on the averaged visibility",
               kTunable),
      floatKey(&X::depthMipSamplingOffset, "depth_mip_sampling_offset", 0.0, 30.0,
               "DepthMIPSamplingOffset: MIP = log2(offset in pixels) - this", kTunable),
      intKey(&X::denoisePasses, "denoise_passes", 1, 3, "DenoisePasses: edge-aware 3x3 passes (1 sharp, 2 medium, 3 soft)"),
      boolKey(&X::depth32, "depth32", "R32F depth MIP chain instead of R16F (XE_GTAO_FP32_DEPTHS)"),
      boolKey(&X::bent, "bent", "bent normals computed and written (XE_GTAO_COMPUTE_BENT_NORMALS)"),
      bindKey(&X::temporal, shared_passes::temporalParameter(0)),
  };
  return table;
}

void addXeGtaoPipeline(FrameBuilder& frame, const Settings& settings) {
  XeGtaoSettings x = xegtaoSettings(settings);
  auto blocks = x.blocks();
  auto mips = shared_passes::addHorizonDepthMips(frame, blocks, "xegtao_prefilter");
  auto working = addXeGtaoMainPass(frame, x, mips);
  auto denoised = shared_passes::addHorizonDenoise(frame, blocks, working, "xegtao_denoise");
  shared_passes::addHorizonSky(frame, blocks, denoised, "xegtao_sky");

  shared_passes::addHorizonDepthViews(frame, mips);
  frame.debugView("view_normals", frame.viewNormals());
  frame.debugView("screen_radius", shared_passes::addHorizonScreenRadius(frame, blocks, mips, "xegtao_screen_radius"));
  frame.debugView("edges", working.edges);
  frame.debugView("ao_raw", working.aoTerm);
  frame.debugView("ao_denoised", denoised);

  shared_passes::DenoiseInput in{denoised, x.bent, 1};
  frame.setOutput(shared_passes::addTemporalDenoise(frame, in),
                  x.bent ? OutputLayout::bentThenVisibility() : OutputLayout::visibilityOnly());
}

Technique makeXeGtao() {
  Technique t;
  t.name = "xegtao";
  t.seed = "002 XeGTAO";
  t.summary = "Intel's XeGTAO: prefiltered depth MIP chain, horizon search with Hilbert/R2 noise, edge-aware denoiser";
  t.parameters = keyTable().parameters();
  t.presets = {{"low", {{"slices", 1}, {"steps", 2}}},
               {"medium", {{"slices", 2}, {"steps", 2}}},
               {"high", {{"slices", 3}, {"steps", 3}}},
               {"ultra", {{"slices", 9}, {"steps", 3}}}};
  t.defaultPreset = "high";
  t.debugViews = shared_passes::horizonDebugViews();
  t.debugViews.insert(t.debugViews.end(), {
      {"ao_raw", "the main pass's working term as stored: round(255 x visibility / 1.5) (bent=1: RGBA8 packed in R32)"},
      {"ao_denoised", "after the last denoise pass and the sky pass, before any temporal pass: visibility (bent=1: RGBA, bent.xyz + visibility)"},
      {"mip_taps", "report.json frames[i].debug.mip_taps: the main pass's depth taps per MIP level 0-4"},
  });
  t.addPasses = addXeGtaoPipeline;
  t.history = shared_passes::temporalDenoiseHistory;
  t.withoutHistory = shared_passes::withoutTemporalDenoise;
  return t;
}

}  // namespace

const Technique& xegtaoTechnique() {
  static const Technique t = makeXeGtao();
  return t;
}

XeGtaoSettings xegtaoSettings(const Settings& settings) { return keyTable().read(settings); }

}  // namespace aor
