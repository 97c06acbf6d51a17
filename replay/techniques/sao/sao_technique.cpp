// Seed 004: the deep G-buffer demo's AO frame, as a technique module: camera-space Z of both depth
// layers -> rotated-grid pyramid -> Scalable Ambient Obscurance (McGuire, Mara, Luebke, HPG 2012;
// the second layer as in the deep G-buffer paper) -> separable bilateral blur. Seed 004 point by
// point: README.md in this folder.
#include "shared_passes/shared_passes.h"
#include "capture/capture.h"
#include "core/input_error.h"
#include "technique_api/key_table.h"
#include "techniques/registry.h"
#include "techniques/sao/sao_settings.h"

namespace aor {
namespace {

constexpr const char* kSamples = "samples";
constexpr const char* kSpiralTurns = "spiral_turns";
constexpr const char* kDualLayer = "dual_layer";

// Every key with its SaoSettings field; defaults are the struct's.
const KeyTable<SaoSettings>& keyTable() {
  using S = SaoSettings;
  static const KeyTable<S> table = {
      radiusKey(&S::radius),
      floatKey(&S::bias, "bias", 0, 1, "beta: obscurance bias along the normal, world units", kTunable),
      floatKey(&S::intensity, "intensity", 0, 16, "sigma: obscurance intensity", kTunable),
      intKey(&S::samples, kSamples, 1, int(kSaoSpiralTurnsTable.size()), "taps per pixel"),
      intKey(&S::spiralTurns, kSpiralTurns, 1, 99, "tau: turns of the tap spiral (presets: the paper's table)"),
      intKey(&S::blurRadius, "blur_radius", 0, 16, "bilateral blur taps on each side of each leg, 0 = no blur"),
      intKey(&S::blurStep, "blur_step", 1, 8, "pixels between blur taps"),
      floatKey(&S::edgeSharpness, "edge_sharpness", 0, 100, "blur's depth edge sharpness, 0 = plain Gaussian", kTunable),
      boolKey(&S::csz32, "csz32", "camera-space Z as R32F instead of R16F"),
      enumKey(&S::dualLayer, kDualLayer, {"0", "1", "auto"},
              "second depth layer: 0 off, 1 on (the capture must have depth2), auto when it has one"),
      bindKey(&S::temporal, shared_passes::temporalParameter(0)),
  };
  return table;
}

void addSaoPipeline(FrameBuilder& frame, const Settings& settings) {
  SaoSettings s = saoSettings(settings);
  bool dualLayer = saoUsesSecondLayer(s, frame.capture());
  // Step 2 of the seed: camera-space Z of every layer, then its pyramid.
  auto csz = addSaoCszPass(frame, s, dualLayer);
  frame.debugView("csz", csz, {0, 1, 0, 1});
  addSaoMinifyPasses(frame, csz);
  uint32_t levels = frame.graph().resources()[csz].desc.mipLevels;
  for (uint32_t level = 1; level < levels; ++level) frame.debugView("csz_mip" + std::to_string(level), csz, {level, 1, 0, 1});
  // Step 3: AO.
  auto raw = addSaoPass(frame, s, dualLayer, csz);
  frame.debugView("ao_raw", raw);
  // Step 4: the blur, horizontal then vertical.
  auto horizontal = addSaoBlurPass(frame, s, raw, csz, true);
  frame.debugView("ao_blur_h", horizontal);
  auto blurred = addSaoBlurPass(frame, s, horizontal, csz, false);
  frame.debugView("ao", blurred);
  // The shared temporal block (temporal > 0 in a multi-frame replay), else the blurred AO itself.
  frame.setOutput(shared_passes::addTemporalDenoise(frame, {blurred, false, 1}), OutputLayout::visibilityOnly());
}

void checkSaoCapture(const Settings& settings, const Capture& capture) {
  SaoSettings s = saoSettings(settings);
  if (s.dualLayer == SaoDualLayer::On && !capture.hasDepth2)
    throw InputError((capture.folder / "capture.json").string(), std::nullopt, kDualLayer, kSaoNoSecondLayer);
}

Preset samplesPreset(const char* name, int samples) {
  return {name, {{kSamples, samples}, {kSpiralTurns, saoSpiralTurnsFor(samples)}}};
}

Technique makeSao() {
  Technique t;
  t.name = "sao";
  t.seed = "004 deep G-buffer AO (SAO with a second depth layer)";
  t.summary = "Scalable Ambient Obscurance on a camera-space Z pyramid, both depth layers where the capture has two, "
              "separable bilateral blur";
  t.parameters = keyTable().parameters();
  t.presets = {samplesPreset("low", 9), samplesPreset("medium", 13), samplesPreset("high", 19), samplesPreset("ultra", 31)};
  t.defaultPreset = "high";
  t.inputs.depth2 = InputUse::Optional;
  t.debugViews = {{"csz", "camera-space Z, level 0 (R layer 0, G layer 1 with the second layer; sky -1)"},
                  {"csz_mip1", "camera-space Z pyramid, level 1 (rotated-grid subsample)"},
                  {"csz_mip2", "camera-space Z pyramid, level 2"},
                  {"csz_mip3", "camera-space Z pyramid, level 3"},
                  {"csz_mip4", "camera-space Z pyramid, level 4"},
                  {"ao_raw", "SAO's visibility before the blur"},
                  {"ao_blur_h", "after the horizontal blur"},
                  {"ao", "after both blur legs (the output unless temporal > 0)"}};
  t.addPasses = addSaoPipeline;
  t.history = shared_passes::temporalDenoiseHistory;
  t.withoutHistory = shared_passes::withoutTemporalDenoise;
  t.checkCapture = checkSaoCapture;
  return t;
}

}  // namespace

SaoSettings saoSettings(const Settings& settings) { return keyTable().read(settings); }

const Technique& saoTechnique() {
  static const Technique t = makeSao();
  return t;
}

}  // namespace aor
