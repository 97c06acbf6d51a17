#pragma once
// How a captured API maps clip space to the depth target's texels, as RenderDoc reports it for the
// draw (never assumed from the byte count or the format), and the exact changes that bring a
// frame to the capture format's conventions (captures/FORMAT.md: Vulkan's clip z in [0, 1], row 0
// at the top, NDC y = -1 there).
#include <optional>
#include <string>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

namespace aor {

struct ApiConventions {
  std::string api;                  // RenderDoc's driver name: "Vulkan", "OpenGL"
  bool clipZMinusOneToOne = false;  // GL's default; Vulkan with VK_EXT_depth_clip_control
  bool clipOriginUpperLeft = false; // GL: glClipControl(GL_UPPER_LEFT, ...): NDC y = +1 at window row 0
  bool rowsBottomUp = false;        // GL: window row 0 (the first texel row) is the picture's bottom
  double depthRangeMin = 0.0, depthRangeMax = 1.0;  // the viewport's: window depth = min + (max - min) * NDC z in [0, 1]
};

// The draw's viewport as the API states it, in texel rows of the depth target (GL: from its
// first row, the bottom; Vulkan: from the top, the height may be negative).
struct RawViewport {
  float x = 0, y = 0, width = 0, height = 0;
};

// The texel row coordinate (continuous, 0 = the first row's edge) that NDC y lands on.
double windowRow(const ApiConventions& c, const RawViewport& v, double ndcY);
// The window depth of NDC z (GL's [-1, 1] range halved, then the viewport's depth range applied).
double windowDepth(const ApiConventions& c, double ndcZ);

// The projection whose clip z over w is the window depth the draw stored: GL's clip z in [-1, 1]
// brought to [0, 1] (row2' = (row2 + row3) / 2), then a viewport depth range [a, b] folded in
// (row2' = a row3 + (b - a) row2). x, y and w are left as they are; unchanged for [0, 1] and [0, 1].
glm::mat4 projectionToWindowDepth(const ApiConventions& c, const glm::mat4& projection);

// Where sample `sample` of a `samples`-sample pixel lies inside it (0..1 from the pixel's top-left
// corner, texel rows as stored): the standard sample locations of Vulkan (and D3D), which the
// device must use when it reports standardSampleLocations; nullopt for a count without a standard
// table. One sample: the centre.
std::optional<glm::dvec2> standardSamplePosition(int samples, int sample);

}  // namespace aor
