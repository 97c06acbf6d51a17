#pragma once
// Seed 000's GTAO pass in a frame's render graph (gtao_pass.cpp); its settings and constants are in
// gtao_settings.h.
#include "technique_api/frame_builder.h"
#include "techniques/gtao/gtao_settings.h"

namespace aor {

// The GTAO pass (shaders/gtao/gtao.comp): writes `ao_noisy` in aoImageFormat(bent) at
// aoWorkingSize. `viewSpaceNormals` tells captured (world space) from reconstructed normals.
struct GtaoInputs {
  graph::ResourceId distance;
  graph::ResourceId normals;
  bool viewSpaceNormals;
};
graph::ResourceId addGtaoPass(FrameBuilder& frame, const GtaoSettings& settings, const GtaoInputs& inputs);
// The normals GTAO reads: the capture's world-space ones, else those reconstructed from depth.
GtaoInputs gtaoInputs(const FrameBuilder& frame);

}  // namespace aor
