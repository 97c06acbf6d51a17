#pragma once
// A camera jump the capture does not mark as a cut (a teleport, a missing "cut" flag) still makes
// the previous output useless as history: the replayer resets history when the camera turns or
// moves further than these limits between two frames.
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace aor {

struct CameraJumpLimits {
  // Defaults: a turn over 45 degrees, or a move longer than the previous frame's median view
  // distance (scale-free: the same rule for a room and a city block). Motion alone cannot tell a
  // cut from a fast camera (a 3-frame orbit of the generator turns 30 degrees and moves 0.75 of the
  // view distance per frame, about what its `cut` path's jump does: 22 degrees, 0.76), so the
  // defaults only catch moves no smooth camera makes; tighten them for captures whose cuts are
  // unmarked. 0 disables a limit.
  float maxRotationDegrees = 45.0f;
  float maxMoveFraction = 1.0f;
};

// Median linear view distance of the frame's surface pixels; 0 when every pixel is sky.
float medianViewDistance(const std::vector<float>& depth, const glm::mat4& projection);

// Why the move from `previousView` to `view` is a jump ("camera jump: turned 61.0 degrees (limit
// 45)"), or empty when it is not.
std::string cameraJumpReason(const glm::mat4& previousView, const glm::mat4& view, float previousMedianDistance,
                             const CameraJumpLimits& limits);

}  // namespace aor
