#pragma once
// Turns the view and projection matrices read from a RenderDoc capture, and the draw's viewport,
// into a capture's camera (captures/FORMAT.md): checked to be a world -> view transform and a
// perspective projection with messages that say what is wrong (a combined matrix, mostly), and
// brought to the format's conventions by exact sign flips where the application's differ.
#include <array>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>

namespace aor {

// RenderDoc gives a matrix's 16 values row by row, whatever the shader declared.
glm::mat4 matrixFromRows(const std::array<float, 16>& rows);

// Throw ImportProblem (field --view / --projection) naming `name` (BLOCK.member) and the problem.
void checkViewMatrix(const glm::mat4& view, const std::string& name);
void checkProjectionMatrix(const glm::mat4& projection, const std::string& name);  // left-handed allowed

// A combined view-projection matrix (P.V, or P.V.M with a rigid model M folded in) split into a
// right-handed perspective projection (clip w = -z_view, P[2][3] = -1) and a rigid world -> view
// transform (a rotation with determinant +1 and a translation), exactly up to rounding. A uniform
// scale folded in cannot be told apart from the projection's near and far planes; a shear or
// non-uniform scale, an orthographic matrix, or a residual above kMaxFactoringResidual throws
// ImportProblem (field --view-projection) naming what it found.
inline constexpr double kMaxFactoringResidual = 1e-5;  // of the matrix's largest entry
struct FactoredViewProjection {
  glm::mat4 view{1.0f}, projection{1.0f};
  double residual = 0;  // largest |P.V - M| over M's largest entry (M scaled so clip w = -z_view)
  double skewDegrees = 0;  // how far the view's x and y axes are from perpendicular
};
FactoredViewProjection factorViewProjection(const glm::mat4& combined, const std::string& name);

// The pixels of the depth target the draw's viewport covers (the capture is cropped to them).
struct ViewportRect {
  int x = 0, y = 0, width = 0, height = 0;
  bool flipsY = false;  // negative viewport height: image rows run up NDC y
};
// Throws ImportProblem (field --event) for a viewport that is fractional, leaves the target, or
// maps depth to one value or outside [0, 1] (other ranges are folded into the projection).
ViewportRect viewportRect(float x, float y, float width, float height, float minDepth, float maxDepth,
                          int targetWidth, int targetHeight);

struct ImportedCamera {
  glm::mat4 view{1.0f}, projection{1.0f};
  std::vector<std::string> adjustments;  // what was changed, for the summary and capture.json
};
// Left-handed view spaces get z flipped (view and projection together, so clip space is
// unchanged); where NDC y = +1 lands on the capture's top row (a negative Vulkan viewport height,
// GL's lower-left origin once its rows are turned top-down) the projection's y is flipped
// instead. Both are exact negations.
ImportedCamera importCamera(const glm::mat4& view, const glm::mat4& projection, bool clipYUpAtTopRow);

// "perspective, standard depth, near 0.1, far 40, vertical field of view 60.0 degrees": the
// planes where the projection's window depth reaches depthA and depthB (a viewport depth range
// folded into it: its ends).
std::string describeProjection(const glm::mat4& projection, double depthA = 0.0, double depthB = 1.0);

// World-space normals from view-space ones of the application's `view` (normals transform with
// the inverse transpose; world from view is therefore view's 3x3 transposed), renormalised.
void viewNormalsToWorld(std::vector<float>& normals, const glm::mat4& view);

}  // namespace aor
