#pragma once
// CPU mirror of the GTAO main pass: the shader's own per-pixel code (shaders/gtao_pixel.glsl)
// compiled as C++, fed with the same inputs the GPU sees (linearised depth, half-precision
// normals). Tests hold the GPU to it; it is also the reference for precision studies.
#include <cstdint>

#include "capture/capture.h"
#include "cpu/ao_image.h"
#include "techniques/gtao/gtao_settings.h"

namespace aor {

// GTAO pass alone (no denoising) on a G-buffer with world-space normals; with half_res=1 the
// image is aoWorkingSize(camera, settings), as the GPU's is. `imageLoads`, when given, receives
// how many times the shader's code loaded a distance or a normal: what the counting build of
// gtao.comp counts as image loads (each load function is one imageLoad there).
CpuAoImage gtaoOnCpu(const GBuffer& gbuffer, const FrameCamera& camera, const GtaoSettings& settings,
                     uint64_t* imageLoads = nullptr);

}  // namespace aor
