#include "passes/camera.h"

#include <cmath>

#include "metrics/depth.h"

namespace aor {

ProjectionParams projectionParams(const glm::mat4& p, int width, int height) {
  ProjectionParams params;
  params.ndcToViewMul = {1.0f / p[0][0], 1.0f / p[1][1]};
  params.ndcToViewAdd = {p[2][0] / p[0][0], p[2][1] / p[1][1]};
  params.viewPerPixel = {2.0f / (float(width) * p[0][0]), 2.0f / (float(height) * p[1][1])};
  params.pixelsPerUnit = std::abs(p[0][0]) * float(width) * 0.5f;
  params.projection22 = p[2][2];
  params.projection32 = p[3][2];
  params.reversedDepth = isReversedDepth(p);
  return params;
}

}  // namespace aor
