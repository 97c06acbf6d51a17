#pragma once
// CPU mirror of the GTAO main pass: the shader's own per-pixel code (shaders/gtao_pixel.glsl)
// compiled as C++, fed with the same inputs the GPU sees (linearised depth, half-precision
// normals). Tests hold the GPU to it; it is also the reference for precision studies.
#include <vector>

#include <glm/glm.hpp>

#include "capture/capture.h"
#include "passes/passes.h"
#include "pipeline/settings.h"

namespace aor {

struct CpuAoImage {
  int width = 0, height = 0;
  std::vector<float> visibility;
  std::vector<glm::vec3> bent;  // view space; empty with bent=0
};

// GTAO pass alone (no denoising) on a G-buffer with world-space normals.
CpuAoImage gtaoOnCpu(const GBuffer& gbuffer, const FrameCamera& camera, const AoSettings& settings);

}  // namespace aor
