#pragma once
// LDR-FLIP (Andersson et al., "FLIP: A Difference Evaluator for Alternating Images", HPG 2020):
// the perceived difference between two images flipped back and forth, per pixel in [0, 1], for
// one-channel images such as AO visibility. AO multiplies lighting, so visibility v is taken as
// linear grey (v, v, v). For grey input the paper's opponent-space chroma channels are zero, and
// its colour pipeline reduces to the HyAB distance between the CIELAB lightness of the two
// CSF-filtered luminances; its feature pipeline (edges and points of the luminance) is unchanged.
// Checked against NVIDIA's own FLIP tool (docs/tuning.md: the command and the numbers).
#include <cstdint>
#include <vector>

namespace aor {

struct FlipOptions {
  // Pixels per degree of visual angle: the paper's default viewer, 0.7 m from a 0.7 m wide
  // 3840-pixel monitor.
  double pixelsPerDegree = 3840.0 * 3.14159265358979323846 / 180.0;
};

// Per-pixel FLIP of `test` against `reference` (both width x height, linear values, clamped to
// [0, 1]); borders clamp to the edge.
std::vector<float> flipErrorMap(const float* reference, const float* test, int width, int height, const FlipOptions& options = {});

// Mean FLIP over the pixels where `mask` is nonzero (all pixels when `mask` is null); 0 when none.
double meanFlip(const float* reference, const float* test, const uint8_t* mask, int width, int height,
                const FlipOptions& options = {});

}  // namespace aor
