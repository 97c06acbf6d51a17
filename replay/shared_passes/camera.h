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

// The camera as techniques written for D3D conventions (XeGTAO, CACAO) take it: view space x right,
// y up, z forward, uv's origin at the top left, z = depthUnpack.x / (depthUnpack.y - depth) and
// view.xy = z (uv * ndcToViewMul + ndcToViewAdd). Derived from this tool's projection, so their own
// handedness fix-ups are not needed; an axis the capture's projection points the other way is
// flipped (axisSigns, which also turn this tool's view-space vectors into theirs with z negated).
struct ForwardViewCamera {
  glm::vec2 depthUnpack{0.0f};
  glm::vec2 tanHalfFov{0.0f};
  glm::vec2 axisSigns{1.0f};
  glm::vec2 ndcToViewMul{0.0f};
  glm::vec2 ndcToViewAdd{0.0f};
};
ForwardViewCamera forwardViewCamera(const ProjectionParams& params);

}  // namespace aor
