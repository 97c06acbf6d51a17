#pragma once
// A camera jump the capture does not mark as a cut (a teleport, a missing "cut" flag) still makes
// the previous output useless as history: the replayer resets history when the camera turns or
// moves further than these limits between two frames.
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace aor {

struct CameraJumpLimits {
  // Defaults: a turn over 30 degrees (the generator's fastest path, a 60-degree orbit over 3 frames,
  // turns exactly 30), or a move over half the previous frame's median view distance (scale-free:
  // the same rule for a room and a city block; such a move changes the size of the scene on screen
  // by up to 2x). 0 disables a limit.
  float maxRotationDegrees = 30.0f;
  float maxMoveFraction = 0.5f;
};

// Median linear view distance of the frame's surface pixels; 0 when every pixel is sky.
float medianViewDistance(const std::vector<float>& depth, const glm::mat4& projection);

// Why the move from `previousView` to `view` is a jump ("camera jump: turned 41.0 degrees (limit
// 30)"), or empty when it is not.
std::string cameraJumpReason(const glm::mat4& previousView, const glm::mat4& view, float previousMedianDistance,
                             const CameraJumpLimits& limits);

}  // namespace aor
