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

ForwardViewCamera forwardViewCamera(const ProjectionParams& params) {
  ForwardViewCamera c;
  // This tool's distance = P32 / (d + P22) is their z = mul / (add - d) with mul = -P32, add = -P22.
  c.depthUnpack = {-params.projection32, -params.projection22};
  // Their 1 / P11 assumes D3D's y-up NDC; this tool's captures have Vulkan's (P11 < 0).
  c.tanHalfFov = glm::abs(params.ndcToViewMul);
  // view.xy = dist * (ndc * mul + add) with ndc = 2 uv - 1; their axes point right and up with uv's
  // origin at the top left, so mul.x > 0 and mul.y < 0 there.
  c.axisSigns = {params.ndcToViewMul.x >= 0.0f ? 1.0f : -1.0f, params.ndcToViewMul.y >= 0.0f ? -1.0f : 1.0f};
  c.ndcToViewMul = 2.0f * params.ndcToViewMul * c.axisSigns;
  c.ndcToViewAdd = (params.ndcToViewAdd - params.ndcToViewMul) * c.axisSigns;
  return c;
}

}  // namespace aor
