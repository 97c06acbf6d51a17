#include "import/api_conventions.h"

namespace aor {

double windowRow(const ApiConventions& c, const RawViewport& v, double ndcY) {
  const double y = c.clipOriginUpperLeft ? -ndcY : ndcY;
  return double(v.y) + (y + 1.0) * 0.5 * double(v.height);
}

double windowDepth(const ApiConventions& c, double ndcZ) {
  const double zeroToOne = c.clipZMinusOneToOne ? (ndcZ + 1.0) * 0.5 : ndcZ;
  return c.depthRangeMin + (c.depthRangeMax - c.depthRangeMin) * zeroToOne;
}

glm::mat4 projectionToWindowDepth(const ApiConventions& c, const glm::mat4& projection) {
  glm::mat4 p = projection;
  if (c.clipZMinusOneToOne)
    for (int column = 0; column < 4; ++column) p[column][2] = (projection[column][2] + projection[column][3]) * 0.5f;
  if (c.depthRangeMin == 0.0 && c.depthRangeMax == 1.0) return p;
  const glm::mat4 zeroToOne = p;
  const float a = float(c.depthRangeMin), scale = float(c.depthRangeMax - c.depthRangeMin);
  for (int column = 0; column < 4; ++column) p[column][2] = a * zeroToOne[column][3] + scale * zeroToOne[column][2];
  return p;
}

std::optional<glm::dvec2> standardSamplePosition(int samples, int sample) {
  // In 1/16 pixel, as the Vulkan specification's table "Standard sample locations" lists them.
  static const int two[][2] = {{12, 12}, {4, 4}};
  static const int four[][2] = {{6, 2}, {14, 6}, {2, 10}, {10, 14}};
  static const int eight[][2] = {{9, 5}, {7, 11}, {13, 9}, {5, 3}, {3, 13}, {1, 7}, {11, 15}, {15, 1}};
  static const int sixteen[][2] = {{9, 9}, {7, 5}, {5, 10}, {12, 7}, {3, 6}, {10, 13}, {13, 11}, {11, 3},
                                   {6, 14}, {8, 1}, {4, 2}, {2, 12}, {0, 8}, {15, 4}, {14, 15}, {1, 0}};
  if (sample < 0 || sample >= samples) return std::nullopt;
  const int(*table)[2] = samples == 2 ? two : samples == 4 ? four : samples == 8 ? eight : samples == 16 ? sixteen : nullptr;
  if (samples == 1) return glm::dvec2(0.5, 0.5);
  if (!table) return std::nullopt;
  return glm::dvec2(table[sample][0] / 16.0, table[sample][1] / 16.0);
}

}  // namespace aor
