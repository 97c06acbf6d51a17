#pragma once
// Where the surface a pixel shows was on screen in the previous frame: the temporal pass's
// rejection layers 1 (off-screen) and 2 (depth mismatch) evaluated on the host with the same shared
// shader functions, so the metrics judge exactly the history the pass was allowed to reuse.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace aor {

// A frame's camera and linear view distances (sky and invalid depth: distance <= 0).
struct FrameGeometry {
  int width = 0, height = 0;
  glm::mat4 view{1.0f}, projection{1.0f};
  std::vector<float> distance;
  bool isSky(size_t pixel) const { return !(distance[pixel] > 0.0f); }
};

FrameGeometry frameGeometry(int width, int height, const float* depth, const glm::mat4& view, const glm::mat4& projection);

enum class PixelHistory : unsigned char {
  Sky,          // no surface in the current frame
  Disoccluded,  // off-screen or a different surface last frame: history must be thrown away
  Reprojected,  // the same surface was at `position` in the previous frame
};

struct Reprojection {
  std::vector<PixelHistory> state;    // per current pixel
  std::vector<glm::vec2> position;    // previous-frame pixel coordinates (pixel centres at integers)
  std::vector<uint32_t> nearest;      // index of the nearest previous pixel (clamped to the image), the
                                      // one the depth test read; meaningful for Reprojected pixels
  size_t count(PixelHistory s) const;
};

// Both frames must have the same size.
Reprojection reproject(const FrameGeometry& current, const FrameGeometry& previous);

// Bilinear read of a width*height image at pixel coordinates (centres at integers), clamped to the
// edge: what the temporal pass's history sampler returns.
float sampleBilinear(const std::vector<float>& image, int width, int height, glm::vec2 position);

}  // namespace aor
