// Seed 000: the GTAO three-pass pipeline (GTAO -> spatial bilateral -> temporal reprojection), as a
// technique module: its keys, presets and passes. Seed 000 point by point: shaders/README.md.
#include "shared_passes/shared_passes.h"
#include "techniques/gtao/gtao_pass.h"
#include "technique_api/key_table.h"
#include "techniques/registry.h"

namespace aor {
namespace {

constexpr const char* kSlices = "slices";
constexpr const char* kSteps = "steps";

// Every key with its GtaoSettings field; defaults are the struct's.
const KeyTable<GtaoSettings>& keyTable() {
  using G = GtaoSettings;
  static const KeyTable<G> table = {
      radiusKey(&G::radius),
      intKey(&G::slices, kSlices, 1, 32, "directions per pixel"),
      intKey(&G::steps, kSteps, 1, 64, "samples per side of a direction"),
      floatKey(&G::falloff, "falloff", 0, 1, "fraction of the radius that fades; 0 = hard cut-off", kTunable),
      floatKey(&G::power, "power", 0.05, 16, "final exponent on visibility, 1 = none", kTunable),
      floatKey(&G::thin, "thin", 0, 8, "thin-occluder compensation, 0 = off", kTunable),
      bindKey(&G::spatial, shared_passes::spatialParameter()),
      bindKey(&G::temporal, shared_passes::temporalParameter(0)),
      boolKey(&G::bent, "bent", "bent normals computed and written (bent.X/Y/Z)"),
      boolKey(&G::halfRes, "half_res", "GTAO and the spatial blur at half resolution, upsampled by the last pass"),
  };
  return table;
}

void addGtaoPipeline(FrameBuilder& frame, const Settings& settings) {
  GtaoSettings g = gtaoSettings(settings);
  auto noisy = addGtaoPass(frame, g, gtaoInputs(frame));
  frame.debugView("linear_depth", frame.linearDistance());
  frame.debugView("ao_raw", noisy);
  shared_passes::DenoiseInput in{noisy, g.bent, aoResolutionDivisor(g)};
  in.ao = shared_passes::addSpatialDenoise(frame, in);
  frame.debugView("ao_denoised", in.ao);
  frame.setOutput(shared_passes::addTemporalDenoise(frame, in),
                  g.bent ? OutputLayout::bentThenVisibility() : OutputLayout::visibilityOnly());
}

Technique makeGtao() {
  Technique t;
  t.name = "gtao";
  t.seed = "000 GTAO three-pass pipeline";
  t.summary = "horizon-search GTAO with bent normals, seed 000's spatial bilateral and temporal reprojection";
  t.parameters = keyTable().parameters();
  t.presets = {{"low", {{kSlices, 1}, {kSteps, 2}}},
               {"medium", {{kSlices, 2}, {kSteps, 2}}},
               {"high", {{kSlices, 3}, {kSteps, 3}}},
               {"ultra", {{kSlices, 9}, {kSteps, 3}}}};
  t.defaultPreset = "high";
  t.debugViews = {{"linear_depth", "the shared front's linear view distance (R32F, sky -1)"},
                  {"ao_raw", "GTAO's output before denoising (visibility in A with bent=1, else R)"},
                  {"ao_denoised", "after the spatial blur (GTAO's output with spatial=0)"}};
  t.addPasses = addGtaoPipeline;
  t.history = shared_passes::temporalDenoiseHistory;
  t.withoutHistory = shared_passes::withoutTemporalDenoise;
  return t;
}

}  // namespace

GtaoSettings gtaoSettings(const Settings& settings) { return keyTable().read(settings); }

Settings gtaoRun(const std::vector<std::string>& assignments) {
  Settings s(findTechnique("gtao"));
  for (const auto& a : assignments) s.assign(a);
  return s;
}

Settings settingsOf(const Technique& technique, const GtaoSettings& values) { return keyTable().write(technique, values); }

const Technique& gtaoTechnique() {
  static const Technique t = makeGtao();
  return t;
}

}  // namespace aor
