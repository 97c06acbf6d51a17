// The visibility-bitmask successor to GTAO (Therrien, Levesque and Gilet 2023; ambient occlusion
// only) as a technique module: its keys, presets (Bevy's slices x steps), debug views and passes.
// The depth MIP chain, noise, denoiser and sky pass are xegtao's, as shared horizon blocks; the
// main pass is its own (vbao_passes.cpp). Point by point: README.md here.
#include "shared_passes/shared_passes.h"
#include "technique_api/key_table.h"
#include "techniques/registry.h"
#include "techniques/vbao/vbao_settings.h"

namespace aor {
namespace {

// Every key with its VbaoSettings field; defaults are the struct's.
const KeyTable<VbaoSettings>& keyTable() {
  using V = VbaoSettings;
  static const KeyTable<V> table = {
      radiusKey(&V::radius),
      intKey(&V::slices, "slices", 1, 32, "slice directions per pixel"),
      intKey(&V::steps, "steps", 1, 32, "samples per side of a slice"),
      floatKey(&V::thickness, "thickness", 0.0, 1e6,
               "world units: every depth sample is a slab this thick behind what it sees (Bevy: 0.25)", kTunable),
      intKey(&V::sectors, "sectors", 0, 32,
             "sectors of a slice's hemisphere in its bit mask (the paper's 32); 0: tied to the samples, 2 x steps "
             "(Bevy's)"),
      enumKey(&V::weighting, "weighting", {"uniform", "cosine"},
              "what an open sector weighs: its share of the hemisphere (uniform, Bevy's) or its cosine-weighted "
              "arc integral as GTAO's (cosine)"),
      floatKey(&V::radiusMultiplier, "radius_multiplier", 0.3, 3.0, "the radius searched is radius x this (XeGTAO's)",
               kTunable),
      floatKey(&V::falloffRange, "falloff_range", 0.0, 1.0,
               "fraction of the radius over which samples fade out (XeGTAO's); 0: a hard edge at the radius", kTunable),
      floatKey(&V::sampleDistributionPower, "sample_distribution_power", 1.0, 3.0,
               "step positions t^power, >1 crowds them towards the centre (XeGTAO's)", kTunable),
      floatKey(&V::finalValuePower, "final_value_power", 0.5, 5.0, "exponent on the averaged visibility", kTunable),
      floatKey(&V::depthMipSamplingOffset, "depth_mip_sampling_offset", 0.0, 30.0,
               "MIP = log2(offset in pixels) - this (XeGTAO's)", kTunable),
      intKey(&V::denoisePasses, "denoise_passes", 1, 3, "the shared edge-aware 3x3 passes (XeGTAO's denoiser)"),
      boolKey(&V::depth32, "depth32", "R32F depth MIP chain instead of R16F"),
      bindKey(&V::temporal, shared_passes::temporalParameter(0)),
  };
  return table;
}

void addVbaoPipeline(FrameBuilder& frame, const Settings& settings) {
  VbaoSettings v = vbaoSettings(settings);
  auto blocks = v.blocks();
  auto mips = shared_passes::addHorizonDepthMips(frame, blocks, "vbao_prefilter");
  auto working = addVbaoMainPass(frame, v, mips);
  auto denoised = shared_passes::addHorizonDenoise(frame, blocks, working, "vbao_denoise");
  shared_passes::addHorizonSky(frame, blocks, denoised, "vbao_sky");

  shared_passes::addHorizonDepthViews(frame, mips);
  frame.debugView("view_normals", frame.viewNormals());
  frame.debugView("screen_radius", shared_passes::addHorizonScreenRadius(frame, blocks, mips, "vbao_screen_radius"));
  frame.debugView("edges", working.edges);
  frame.debugView("ao_raw", working.aoTerm);
  frame.debugView("ao_denoised", denoised);

  shared_passes::DenoiseInput in{denoised, false, 1};
  frame.setOutput(shared_passes::addTemporalDenoise(frame, in), OutputLayout::visibilityOnly());
}

Technique makeVbao() {
  Technique t;
  t.name = "vbao";
  t.summary = "visibility bitmask (Therrien et al. 2023): xegtao's samples as slabs of a thickness marking sectors, "
              "xegtao's depth chain and denoiser";
  t.parameters = keyTable().parameters();
  t.presets = {{"low", {{"slices", 1}, {"steps", 2}}},
               {"medium", {{"slices", 2}, {"steps", 2}}},
               {"high", {{"slices", 3}, {"steps", 3}}},
               {"ultra", {{"slices", 9}, {"steps", 3}}}};
  t.defaultPreset = "high";
  t.debugViews = shared_passes::horizonDebugViews();
  t.debugViews.insert(t.debugViews.end(), {
      {"ao_raw", "raw visibility as the main pass stores it: round(255 x visibility / 1.5)"},
      {"sectors", "the share of a slice's sectors occupied, averaged over the slices (R32F)"},
      {"ao_denoised", "after the last denoise pass and the sky pass, before any temporal pass"},
  });
  t.addPasses = addVbaoPipeline;
  t.history = shared_passes::temporalDenoiseHistory;
  t.withoutHistory = shared_passes::withoutTemporalDenoise;
  return t;
}

}  // namespace

const Technique& vbaoTechnique() {
  static const Technique t = makeVbao();
  return t;
}

VbaoSettings vbaoSettings(const Settings& settings) { return keyTable().read(settings); }

}  // namespace aor
