#include "metrics/depth.h"

#include "blocks/linearize_depth.h"

namespace aor {

void linearViewDistances(std::span<const float> depth, const glm::mat4& projection, std::span<float> distances) {
  bool reversed = isReversedDepth(projection);
  for (size_t i = 0; i < depth.size(); ++i)
    distances[i] = shader::linearViewDistance(depth[i], projection[2][2], projection[3][2], reversed);
}

std::vector<float> linearViewDistances(std::span<const float> depth, const glm::mat4& projection) {
  std::vector<float> distances(depth.size());
  linearViewDistances(depth, projection, distances);
  return distances;
}

}  // namespace aor
