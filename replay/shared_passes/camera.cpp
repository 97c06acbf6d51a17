#include "shared_passes/camera.h"

#include <cmath>

#include "common/common.h"
#include "metrics/depth.h"

namespace aor {

ProjectionParams projectionParams(const glm::mat4& p, int width, int height) {
  ProjectionParams params;
  params.ndcToViewMul = shader::ndcToViewMulOf(p);
  params.ndcToViewAdd = shader::ndcToViewAddOf(p);
  params.viewPerPixel = {2.0f / (float(width) * p[0][0]), 2.0f / (float(height) * p[1][1])};
  params.pixelsPerUnit = std::abs(p[0][0]) * float(width) * 0.5f;
  params.projection22 = p[2][2];
  params.projection32 = p[3][2];
  params.reversedDepth = isReversedDepth(p);
  return params;
}

}  // namespace aor
