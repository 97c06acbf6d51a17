#include "metrics/depth.h"

#include "linearize_depth.h"

namespace aor {

std::vector<float> linearViewDistances(std::span<const float> depth, const glm::mat4& projection) {
  bool reversed = isReversedDepth(projection);
  std::vector<float> distances(depth.size());
  for (size_t i = 0; i < depth.size(); ++i)
    distances[i] = shader::linearViewDistance(depth[i], projection[2][2], projection[3][2], reversed);
  return distances;
}

}  // namespace aor
