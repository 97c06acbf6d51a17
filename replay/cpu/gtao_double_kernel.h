#pragma once
// The GTAO pixel code (shaders/gtao_pixel.glsl) compiled with every float replaced by double.
// Kept apart from gtao_double.cpp because that translation unit must not see the float shader
// headers (both define the same names). Inputs are plain doubles; see gtao_double.h for the model.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "cpu/ao_image.h"

namespace aor {

struct DoubleGtaoInputs {
  glm::dvec2 ndcToViewMul{1.0}, ndcToViewAdd{0.0}, invSize{1.0}, viewPerPixel{1.0};
  glm::ivec2 size{0};
  double radius = 1, pixelsPerUnit = 1, falloffRange = 0, thin = 0, power = 1;
  int slices = 1, steps = 1;
  bool bent = false;
  std::vector<double> distance;      // linear view distance per pixel, <= 0 for sky/invalid
  std::vector<glm::dvec3> normals;   // view-space normals as the GPU fetches them (not normalised)
  std::vector<glm::vec2> noise;      // per-pixel (direction, step) noise from the float shader code,
                                     // which is where the frame index enters
};

// gtaoPixel of the shader in double arithmetic over every pixel of inputs.size.
DoubleAoImage gtaoImageDouble(const DoubleGtaoInputs& inputs);

// linearViewDistance of the shader (linearize_depth.h) in double arithmetic.
double linearViewDistanceDouble(double depth, double projection22, double projection32, bool reversedDepth);

}  // namespace aor
