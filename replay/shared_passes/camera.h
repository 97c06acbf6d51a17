#pragma once
// Quantities every pass derives from a frame's perspective projection (capture format v1).
#include <glm/glm.hpp>

namespace aor {

struct ProjectionParams {
  glm::vec2 ndcToViewMul{1.0f};  // view.xy = dist * (ndc * mul + add)
  glm::vec2 ndcToViewAdd{0.0f};
  glm::vec2 viewPerPixel{0.0f};  // view-space xy per pixel at distance 1 (signed)
  float pixelsPerUnit = 1.0f;    // pixels per view unit at distance 1 (horizontal)
  float projection22 = 0.0f;
  float projection32 = 0.0f;
  bool reversedDepth = false;    // near maps to 1, far to 0
};

ProjectionParams projectionParams(const glm::mat4& projection, int width, int height);

}  // namespace aor
