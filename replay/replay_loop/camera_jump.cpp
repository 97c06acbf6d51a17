#include "replay_loop/camera_jump.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "metrics/depth.h"

namespace aor {

float medianViewDistance(const std::vector<float>& depth, const glm::mat4& projection) {
  std::vector<float> distances = linearViewDistances(depth, projection);
  std::erase_if(distances, [](float distance) { return !(distance > 0.0f); });  // sky and invalid depth
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
