#pragma once
// Double-precision model of the GTAO main pass, the yardstick for float32 drift (PRECISION.md):
// the same shader code (gtao_pixel.glsl, linearize_depth.h) compiled with double arithmetic, the
// same sample pattern (noise and sample pixels taken from the float code) and the same inputs the
// GPU receives (float depth, half-precision normals). Everything derived from them (projection
// terms, linear distance, view positions, angles, integrals) is computed in double.
#include <cstddef>
#include <vector>

#include "capture/capture.h"
#include "cpu/ao_image.h"
#include "techniques/gtao/gtao_settings.h"

namespace aor {

DoubleAoImage gtaoOnCpuDouble(const GBuffer& gbuffer, const FrameCamera& camera, const GtaoSettings& settings);

// How far a float32 visibility image is from the double model: maximum and 99th percentile of
// |float - double| over all pixels, and where the maximum is.
struct Deviation {
  double max = 0, p99 = 0;
  size_t worstPixel = 0;
};
Deviation visibilityDeviation(const DoubleAoImage& model, const std::vector<float>& visibility);

}  // namespace aor
