#pragma once
// Seed 004's SAO pipeline (CSZ -> pyramid -> SAO -> separable bilateral blur): its settings as the
// passes use them, read from a run's Settings, and the passes themselves (sao_passes.cpp). The
// keys are declared once, in sao_technique.cpp.
#include <array>

#include "sao/sao.h"
#include "technique_api/frame_builder.h"
#include "technique_api/settings.h"

namespace aor {

// `dual_layer`: an enum whose first two choices' indices are their meanings.
enum class SaoDualLayer { Off = 0, On = 1, Auto = 2 };

struct SaoSettings {
  float radius = 0.75f;  // world units
  float bias = 0.023f;   // beta
  float intensity = 1.0f;  // sigma
  int samples = 19;
  int spiralTurns = 7;   // tau
  int blurRadius = 4;    // taps on each side of each leg
  int blurStep = 2;      // pixels between blur taps
  float edgeSharpness = 1.0f;
  bool csz32 = false;    // R32F camera-space Z instead of R16F
  SaoDualLayer dualLayer = SaoDualLayer::Auto;
  float temporal = 0.0f;  // seed 000's temporal block, off by default
};

SaoSettings saoSettings(const Settings& settings);

// The spiral turns tau the table accompanying the SAO paper's code lists for 1..40 taps (its
// ROTATIONS[n - 1]): chosen so that no two taps line up.
inline constexpr std::array<int, 40> kSaoSpiralTurnsTable = {
    1, 1, 2, 3, 2, 5, 2, 3, 2,                 // 1-9
    3, 3, 5, 5, 3, 4, 7, 5, 5, 7,              // 10-19
    9, 8, 5, 5, 7, 7, 7, 8, 5, 8,              // 20-29
    11, 12, 7, 10, 13, 8, 11, 8, 7, 14, 11};   // 30-40
inline constexpr int saoSpiralTurnsFor(int samples) { return kSaoSpiralTurnsTable.at(size_t(samples - 1)); }

// Whether the run takes the second layer: dual_layer=1, or auto on a capture that has one.
// dual_layer=1 without one throws InputError (checked before the replay too: checkCapture).
bool saoUsesSecondLayer(const SaoSettings& settings, const CaptureLayout& capture);
extern const char* const kSaoNoSecondLayer;  // what both say

// The CSZ pyramid's format: R16F (R32F with csz32=1), RG with the second layer.
VkFormat saoCszFormat(bool csz32, bool dualLayer);
// Levels of the pyramid at this size: kSaoMipLevels, fewer where the frame is too small for them.
uint32_t saoMipLevels(uint32_t width, uint32_t height);

// The passes, in order. `csz` (level 0) from both depth layers; `csz_mip1..` below it; `sao`
// writes `ao_raw`; the blur's two legs write `ao_blur_h` and `ao_blur`.
graph::ResourceId addSaoCszPass(FrameBuilder& frame, const SaoSettings& settings, bool dualLayer);
void addSaoMinifyPasses(FrameBuilder& frame, graph::ResourceId csz);
graph::ResourceId addSaoPass(FrameBuilder& frame, const SaoSettings& settings, bool dualLayer, graph::ResourceId csz);
graph::ResourceId addSaoBlurPass(FrameBuilder& frame, const SaoSettings& settings, graph::ResourceId ao,
                                 graph::ResourceId csz, bool horizontal);

}  // namespace aor
