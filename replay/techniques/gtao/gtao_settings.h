#pragma once
// Seed 000's GTAO pipeline (GTAO -> spatial -> temporal): its settings as the shaders and the CPU
// mirror use them, read from a run's Settings, and the per-frame constants of the GTAO pass. The
// keys themselves are declared once, in gtao_technique.cpp; the passes are in gtao_pass.h.
// Nothing here needs a device: the CPU mirror (replay/cpu/) computes the same constants.
#include <glm/glm.hpp>

#include "gtao/gtao.h"
#include "technique_api/frame_camera.h"
#include "technique_api/settings.h"

namespace aor {

struct GtaoSettings {
  float radius = 1.0f;  // world units
  int slices = 3, steps = 3;
  float falloff = shader::kGtaoFalloffRange;  // fraction of the radius over which sample weight fades
  float power = 1.0f;                         // final exponent
  float thin = 0.0f;                          // thin-occluder compensation
  bool spatial = true;
  float temporal = 0.9f;  // history weight; 0 = no temporal pass
  bool bent = true;
  bool halfRes = false;   // GTAO and the spatial blur at half resolution, upsampled in the last pass
};

// The values of a gtao run's keys (or, for another technique built on the same integral, of the
// keys it declares; the rest keep the defaults above).
GtaoSettings gtaoSettings(const Settings& settings);
// `gtao` Settings for tests and tools: the technique's defaults with these assignments.
Settings gtaoRun(const std::vector<std::string>& assignments = {});
// Settings of `technique` (gtao, or one built on the same integral such as reference) holding these
// values for every key it declares; its other keys keep their defaults.
Settings settingsOf(const Technique& technique, const GtaoSettings& values);

// GTAO and the spatial blur work on one texel per divisor x divisor pixels: 1, or 2 with half_res=1.
inline int aoResolutionDivisor(const GtaoSettings& s) { return s.halfRes ? 2 : 1; }
// Size of the images they write: shader::reducedSize of the frame's by that divisor.
glm::ivec2 aoWorkingSize(const FrameCamera& camera, const GtaoSettings& settings);
// Push constants of the GTAO pass for a frame (shared with the CPU mirror).
shader::GtaoConstants gtaoConstants(const FrameCamera& camera, const GtaoSettings& settings);

}  // namespace aor
