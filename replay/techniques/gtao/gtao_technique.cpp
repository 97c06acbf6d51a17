// Seed 000: the GTAO three-pass pipeline (GTAO -> spatial bilateral -> temporal reprojection), as a
// technique module: its keys, presets and passes. Seed 000 point by point: shaders/README.md.
#include "blocks/blocks.h"
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
  blocks::DenoiseInput in{noisy, g.bent, aoResolutionDivisor(g)};
  in.ao = blocks::addSeed000Spatial(frame, in);
  frame.debugView("ao_denoised", in.ao);
  frame.setOutput(blocks::addSeed000Temporal(frame, in),
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
      blocks::spatialParameter(),
      blocks::temporalParameter(0.9),
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
  t.history = blocks::seed000TemporalHistory;
  t.withoutHistory = [](const Settings& s) -> std::optional<Settings> {
    Settings without = s;
    without.set(blocks::kTemporalKey, 0);
    return without;
  };
  return t;
}

}  // namespace

GtaoSettings gtaoSettings(const Settings& s) {
  GtaoSettings g;
  auto read = [&](const char* key, auto& field) {
    if (s.has(key)) field = static_cast<std::decay_t<decltype(field)>>(s.value(key));
  };
  read(kRadiusKey, g.radius);
  read(kSlices, g.slices);
  read(kSteps, g.steps);
  read(kFalloff, g.falloff);
  read(kPower, g.power);
  read(kThin, g.thin);
  read(blocks::kSpatialKey, g.spatial);
  read(blocks::kTemporalKey, g.temporal);
  read(kBent, g.bent);
  read(kHalfRes, g.halfRes);
  return g;
}

Settings gtaoRun(const std::vector<std::string>& assignments) {
  Settings s(findTechnique("gtao"));
  for (const auto& a : assignments) s.assign(a);
  return s;
}

Settings settingsOf(const Technique& technique, const GtaoSettings& g) {
  Settings s(technique);
  auto write = [&](const char* key, double value) {
    if (s.has(key)) s.set(key, value);
  };
  write(kRadiusKey, g.radius);
  write(kSlices, g.slices);
  write(kSteps, g.steps);
  write(kFalloff, g.falloff);
  write(kPower, g.power);
  write(kThin, g.thin);
  write(blocks::kSpatialKey, g.spatial);
  write(blocks::kTemporalKey, g.temporal);
  write(kBent, g.bent);
  write(kHalfRes, g.halfRes);
  return s;
}

const Technique& gtaoTechnique() {
  static const Technique t = makeGtao();
  return t;
}

}  // namespace aor
