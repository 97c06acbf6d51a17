// Compiles shaders/gtao_pixel.glsl and linearize_depth.h a second time with `float` and the vec
// types redefined as double, in their own namespace, so the double model runs the shader's own
// code path. Constants keep their float literals (same kPi, same thresholds as the shader).
#include "cpu/gtao_double_kernel.h"

#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

namespace aor::shader_double {
// The shader clamps doubles against float literals; GLM's clamp template needs one type.
inline double clamp(double x, double lo, double hi) { return glm::clamp(x, lo, hi); }
}  // namespace aor::shader_double

#define shader shader_double
#define float double
#define vec2 dvec2
#define vec3 dvec3
#define vec4 dvec4
#include "gtao/gtao.h"
#include "blocks/linearize_depth.h"

namespace aor::shader_double {
namespace {

// Everything gtao_pixel.glsl expects from its includer, plus two hooks that keep the sample
// pattern identical to the float shader (member names win over namespace functions inside it):
// the noise comes precomputed from the float code, and sample offsets are rounded from their
// float32 value, so both models read the same pixels and differ only in arithmetic.
struct GtaoDoublePixel {
  GtaoConstants pc;
  int kSlices;
  int kSteps;
  bool kBent;
  bool kThin;
  const DoubleGtaoInputs* in;

  size_t index(ivec2 pixel) const { return size_t(pixel.y) * size_t(pc.size.x) + size_t(pixel.x); }
  double gtaoLoadDistance(ivec2 pixel) const { return in->distance[index(pixel)]; }
  dvec3 gtaoLoadViewNormal(ivec2 pixel) const { return in->normals[index(pixel)]; }
  dvec2 gtaoNoise(ivec2 pixel, uint) const { return dvec2(in->noise[index(pixel)]); }
  static dvec2 round(dvec2 offset) { return dvec2(glm::round(glm::vec2(offset))); }
#include "gtao/gtao_pixel.glsl"
};

}  // namespace
}  // namespace aor::shader_double

#undef shader
#undef float
#undef vec2
#undef vec3
#undef vec4

namespace aor {

DoubleAoImage gtaoImageDouble(const DoubleGtaoInputs& inputs) {
  shader_double::GtaoConstants pc{};  // frameIndex stays 0: the noise hook reads inputs.noise instead
  pc.ndcToViewMul = inputs.ndcToViewMul;
  pc.ndcToViewAdd = inputs.ndcToViewAdd;
  pc.invSize = inputs.invSize;
  pc.size = inputs.size;
  pc.radius = inputs.radius;
  pc.pixelsPerUnit = inputs.pixelsPerUnit;
  pc.falloffRange = inputs.falloffRange;
  pc.thin = inputs.thin;
  pc.power = inputs.power;
  pc.viewPerPixel = inputs.viewPerPixel;
  shader_double::GtaoDoublePixel kernel{pc, inputs.slices, inputs.steps, inputs.bent, pc.thin > 0, &inputs};
  return computeAoImage<double>(inputs.size.x, inputs.size.y, inputs.bent,
                                [&](glm::ivec2 p, glm::dvec3& bent) { return kernel.gtaoPixel(p, bent); });
}

double linearViewDistanceDouble(double depth, double projection22, double projection32, bool reversedDepth) {
  return shader_double::linearViewDistance(depth, projection22, projection32, reversedDepth);
}

}  // namespace aor
