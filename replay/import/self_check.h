#pragma once
// The import's self-check: the imported frame (its depth, rows and camera) against the chosen
// draw's own output of the vertex shader, which RenderDoc replays. Two tests:
//  (a) the projection's depth row must give every on-screen vertex its clip z from its w;
//  (b) at points inside the draw's triangles (at least half a pixel from every edge), the depth the
//      rasteriser wrote (z/w interpolated, exact for a plane) must be what the imported capture
//      holds there through the imported projection, where no nearer surface hides the point.
// A wrong projection fails (a); a wrong decoding, row order or depth convention fails (b).
#include <cstddef>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include "import/api_conventions.h"
#include "import/renderdoc_camera.h"

namespace aor {

// Documented limits (replay/import/README.md, "The self-check").
inline constexpr double kSelfCheckMaxDepthRowResidual = 1e-4;  // NDC units, (a)
inline constexpr size_t kSelfCheckMinPoints = 16;              // unoccluded points, (b)
inline constexpr double kSelfCheckMinMatchFraction = 0.9;      // of the unoccluded points, (b)
inline constexpr int kSelfCheckPointsPerTriangle = 256;        // at most, spread over it

struct SelfCheckInput {
  std::vector<glm::vec4> corners;  // clip x, y, z, w; three per triangle
  ApiConventions conventions;
  RawViewport viewport;
  ViewportRect rect;               // the crop of the depth target the capture holds
  const std::vector<float>* depth = nullptr;  // the capture's depth, rect.width x rect.height, row 0 on top
  glm::mat4 appProjection{1.0f};      // as the draw's shaders hold it
  glm::mat4 captureProjection{1.0f};  // as the capture holds it
  double depthQuantum = 0.0;          // one step of a unorm format; 0 for float depth
  glm::dvec2 samplePosition{0.5, 0.5};  // where the depth's sample lies in its pixel (multisampled: not the centre)
};

// (a) alone: the largest |clip z - P's depth row at that w| / w over the on-screen corners.
double depthRowResidual(const std::vector<glm::vec4>& corners, const glm::mat4& projection);

struct SelfCheckResult {
  size_t vertices = 0, verticesOnScreen = 0;
  double depthRowResidual = 0.0;  // largest, over the on-screen vertices
  size_t triangles = 0, points = 0, hidden = 0, matched = 0, disagreed = 0;
  double worstDifference = 0.0;   // largest |imported - drawn| window depth of a disagreeing point
  int worstX = -1, worstY = -1;   // its capture pixel
  double worstImported = 0.0, worstDrawn = 0.0;
  bool depthRowPassed() const;
  bool depthPassed() const;
};

SelfCheckResult runSelfCheck(const SelfCheckInput& input);

}  // namespace aor
