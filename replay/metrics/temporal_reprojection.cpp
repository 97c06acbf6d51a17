#include "metrics/temporal_reprojection.h"

#include <algorithm>
#include <cmath>

#include "metrics/depth.h"
#include "core/parallel_rows.h"
#include "blocks/temporal_denoise.h"

namespace aor {

FrameGeometry frameGeometry(int width, int height, const float* depth, const glm::mat4& view, const glm::mat4& projection) {
  FrameGeometry g{width, height, view, projection, {}};
  g.distance.resize(size_t(width) * size_t(height));
  forEachRowBand(height, [&](int firstRow, int endRow) {
    size_t first = size_t(firstRow) * size_t(width), count = size_t(endRow - firstRow) * size_t(width);
    linearViewDistances({depth + first, count}, projection, {g.distance.data() + first, count});
  });
  return g;
}

size_t Reprojection::count(PixelHistory s) const { return size_t(std::count(state.begin(), state.end(), s)); }

Reprojection reproject(const FrameGeometry& current, const FrameGeometry& previous) {
  // The temporal pass's own terms, so this judges exactly the history the pass may reuse.
  auto t = shader::temporalReprojection(current.view, current.projection, previous.view, previous.projection,
                                        current.width, current.height);
  glm::vec2 size(float(current.width), float(current.height));
  glm::ivec2 last(current.width - 1, current.height - 1);

  Reprojection r;
  size_t pixels = current.distance.size();
  r.state.assign(pixels, PixelHistory::Sky);
  r.position.assign(pixels, glm::vec2(0.0f));
  r.nearest.assign(pixels, 0);
  forEachRowBand(current.height, [&](int firstRow, int endRow) {
    for (int y = firstRow; y < endRow; ++y)
      for (int x = 0; x < current.width; ++x) {
        size_t i = size_t(y) * size_t(current.width) + size_t(x);
        float dist = current.distance[i];
        if (!(dist > 0.0f)) continue;
        r.state[i] = PixelHistory::Disoccluded;
        glm::vec3 viewPos = shader::viewPositionFromNdc(shader::pixelToNdc(glm::vec2(x, y), t.invSize), dist,
                                                        t.ndcToViewMul, t.ndcToViewAdd);
        glm::vec3 previousView = glm::vec3(t.viewToPreviousView * glm::vec4(viewPos, 1.0f));
        float expected = -previousView.z;
        if (!(expected > 0.0f)) continue;
        glm::vec2 uv = shader::previousNdc(previousView, t.previousProjection) * 0.5f + 0.5f;
        if (!(uv.x >= 0.0f && uv.y >= 0.0f && uv.x <= 1.0f && uv.y <= 1.0f)) continue;
        glm::vec2 position = uv * size - 0.5f;
        glm::ivec2 p = glm::clamp(glm::ivec2(glm::round(position)), glm::ivec2(0), last);
        size_t nearest = size_t(p.y) * size_t(current.width) + size_t(p.x);
        r.position[i] = position;
        r.nearest[i] = uint32_t(nearest);
        if (shader::depthConsistent(expected, previous.distance[nearest], shader::kTemporalDepthTolerance))
          r.state[i] = PixelHistory::Reprojected;
      }
  });
  return r;
}

float sampleBilinear(const std::vector<float>& image, int width, int height, glm::vec2 position) {
  auto at = [&](int x, int y) {
    x = std::clamp(x, 0, width - 1);
    y = std::clamp(y, 0, height - 1);
    return image[size_t(y) * size_t(width) + size_t(x)];
  };
  glm::vec2 base = glm::floor(position);
  glm::vec2 f = position - base;
  int x = int(base.x), y = int(base.y);
  float top = at(x, y) * (1.0f - f.x) + at(x + 1, y) * f.x;
  float bottom = at(x, y + 1) * (1.0f - f.x) + at(x + 1, y + 1) * f.x;
  return top * (1.0f - f.y) + bottom * f.y;
}

}  // namespace aor
