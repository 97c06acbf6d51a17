// Seed 000: the GTAO three-pass pipeline (GTAO -> spatial bilateral -> temporal reprojection), as a
// technique module: its keys, presets and passes. Seed 000 point by point: shaders/README.md.
#include "shared_passes/shared_passes.h"
#include "techniques/gtao/gtao_settings.h"
#include "techniques/registry.h"

namespace aor {
namespace {

constexpr const char* kSlices = "slices";
constexpr const char* kSteps = "steps";
constexpr const char* kFalloff = "falloff";
constexpr const char* kPower = "power";
constexpr const char* kThin = "thin";
constexpr const char* kBent = "bent";
constexpr const char* kHalfRes = "half_res";

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
  t.parameters = {
      radiusParameter(1.0),
      intParameter(kSlices, 3, 1, 32, "directions per pixel"),
      intParameter(kSteps, 3, 1, 64, "samples per side of a direction"),
      floatParameter(kFalloff, shader::kGtaoFalloffRange, 0, 1, "fraction of the radius that fades; 0 = hard cut-off", true),
      floatParameter(kPower, 1, 0.05, 16, "final exponent on visibility, 1 = none", true),
      floatParameter(kThin, 0, 0, 8, "thin-occluder compensation, 0 = off", true),
      shared_passes::spatialParameter(),
      shared_passes::temporalParameter(0.9),
      boolParameter(kBent, true, "bent normals computed and written (bent.X/Y/Z)"),
      boolParameter(kHalfRes, false, "GTAO and the spatial blur at half resolution, upsampled by the last pass"),
  };
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

// Every key with its GtaoSettings field: the one place the two are paired.
template <typename Settings, typename Visit>
void forEachKey(Settings& g, Visit&& visit) {
  visit(kRadiusKey, g.radius);
  visit(kSlices, g.slices);
  visit(kSteps, g.steps);
  visit(kFalloff, g.falloff);
  visit(kPower, g.power);
  visit(kThin, g.thin);
  visit(shared_passes::kSpatialKey, g.spatial);
  visit(shared_passes::kTemporalKey, g.temporal);
  visit(kBent, g.bent);
  visit(kHalfRes, g.halfRes);
}

GtaoSettings gtaoSettings(const Settings& s) {
  GtaoSettings g;
  forEachKey(g, [&](const char* key, auto& field) {
    if (s.has(key)) field = static_cast<std::decay_t<decltype(field)>>(s.value(key));
  });
  return g;
}

Settings gtaoRun(const std::vector<std::string>& assignments) {
  Settings s(findTechnique("gtao"));
  for (const auto& a : assignments) s.assign(a);
  return s;
}

Settings settingsOf(const Technique& technique, const GtaoSettings& g) {
  Settings s(technique);
  forEachKey(g, [&](const char* key, const auto& field) {
    if (s.has(key)) s.set(key, double(field));
  });
  return s;
}

const Technique& gtaoTechnique() {
  static const Technique t = makeGtao();
  return t;
}

}  // namespace aor
