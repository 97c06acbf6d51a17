#include "pipeline/camera_jump.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "linearize_depth.h"

namespace aor {

float medianViewDistance(const std::vector<float>& depth, const glm::mat4& projection) {
  bool reversed = projection[3][2] > 0.0f;
  std::vector<float> distances;
  distances.reserve(depth.size());
  for (float d : depth) {
    float distance = shader::linearViewDistance(d, projection[2][2], projection[3][2], reversed);
    if (distance > 0.0f) distances.push_back(distance);
  }
  if (distances.empty()) return 0.0f;
  auto middle = distances.begin() + std::ptrdiff_t(distances.size() / 2);
  std::nth_element(distances.begin(), middle, distances.end());
  return *middle;
}

std::string cameraJumpReason(const glm::mat4& previousView, const glm::mat4& view, float previousMedianDistance,
                             const CameraJumpLimits& limits) {
  // Relative rotation of the two camera frames; its angle from the trace.
  glm::mat3 relative = glm::mat3(view) * glm::transpose(glm::mat3(previousView));
  float cosine = std::clamp((relative[0][0] + relative[1][1] + relative[2][2] - 1.0f) * 0.5f, -1.0f, 1.0f);
  float degrees = glm::degrees(std::acos(cosine));
  if (limits.maxRotationDegrees > 0.0f && degrees > limits.maxRotationDegrees)
    return fmt::format("camera jump: turned {:.1f} degrees (limit {:g})", degrees, limits.maxRotationDegrees);
  float moved = glm::length(glm::vec3(glm::inverse(view)[3]) - glm::vec3(glm::inverse(previousView)[3]));
  float limit = limits.maxMoveFraction * previousMedianDistance;
  if (limits.maxMoveFraction > 0.0f && previousMedianDistance > 0.0f && moved > limit)
    return fmt::format("camera jump: moved {:.3g} (limit {:g} x median view distance {:.3g})", moved,
                       limits.maxMoveFraction, previousMedianDistance);
  return {};
}

}  // namespace aor
