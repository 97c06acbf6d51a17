#include "cpu/gtao_double.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/gtc/packing.hpp>

#include "cpu/gtao_double_kernel.h"
#include "gtao/gtao.h"
#include "metrics/depth.h"
#include "core/percentile.h"

namespace aor {
namespace {

// Projection terms of passes/camera.cpp, derived in double from the capture's float matrix.
void setProjection(DoubleGtaoInputs& in, const glm::mat4& p, int width, int height) {
  double p00 = p[0][0], p11 = p[1][1];
  in.ndcToViewMul = {1.0 / p00, 1.0 / p11};
  in.ndcToViewAdd = {double(p[2][0]) / p00, double(p[2][1]) / p11};
  in.viewPerPixel = {2.0 / (width * p00), 2.0 / (height * p11)};
  in.pixelsPerUnit = std::abs(p00) * width * 0.5;
  in.invSize = {1.0 / width, 1.0 / height};
  in.size = {width, height};
}

// What the GPU's normal fetch sees: half-precision world normals rotated to view space (the
// shader code normalises them).
glm::dvec3 viewNormal(const GBuffer& gbuffer, size_t i, const glm::dmat3& worldToView) {
  glm::dvec3 n;
  for (int c = 0; c < 3; ++c)
    n[c] = glm::unpackHalf1x16(glm::packHalf1x16(gbuffer.normals[3 * i + size_t(c)]));
  return worldToView * n;
}

}  // namespace

DoubleAoImage gtaoOnCpuDouble(const GBuffer& gbuffer, const FrameCamera& camera, const GtaoSettings& settings) {
  if (!gbuffer.normals.size()) throw std::invalid_argument("gtaoOnCpuDouble: needs captured normals");
  DoubleGtaoInputs in;
  setProjection(in, camera.projection, camera.width, camera.height);
  in.radius = settings.radius;
  in.falloffRange = settings.falloff;
  in.thin = settings.thin;
  in.power = settings.power;
  in.slices = settings.slices;
  in.steps = settings.steps;
  in.bent = settings.bent != 0;

  const glm::mat4& p = camera.projection;
  bool reversed = isReversedDepth(p);
  glm::dmat3 worldToView(glm::dmat4(camera.view));
  size_t pixels = size_t(camera.width) * size_t(camera.height);
  in.distance.resize(pixels);
  in.normals.resize(pixels);
  in.noise.resize(pixels);
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      size_t i = size_t(y) * size_t(camera.width) + size_t(x);
      in.distance[i] = linearViewDistanceDouble(gbuffer.depth[i], p[2][2], p[3][2], reversed);
      in.normals[i] = viewNormal(gbuffer, i, worldToView);
      in.noise[i] = shader::gtaoNoise(glm::ivec2(x, y), camera.frameIndex);  // the float shader's own noise
    }
  return gtaoImageDouble(in);
}

Deviation visibilityDeviation(const DoubleAoImage& model, const std::vector<float>& visibility) {
  if (model.visibility.size() != visibility.size() || visibility.empty())
    throw std::invalid_argument("visibilityDeviation: image sizes differ");
  std::vector<double> errors(visibility.size());
  Deviation d;
  for (size_t i = 0; i < errors.size(); ++i) {
    errors[i] = std::abs(double(visibility[i]) - model.visibility[i]);
    if (!(errors[i] <= d.max)) {  // NaN counts as the worst
      d.max = errors[i];
      d.worstPixel = i;
    }
  }
  d.p99 = nearestRankPercentile(std::move(errors), 0.99);
  return d;
}

}  // namespace aor
