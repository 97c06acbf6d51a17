#pragma once
// A frame's camera and the capture's layout as a technique's constants see them: plain values, no
// device, so the CPU mirrors compute the same constants as the passes.
#include <cstdint>

#include <glm/glm.hpp>

namespace aor {

struct FrameCamera {
  glm::mat4 view{1.0f};
  glm::mat4 projection{1.0f};
  int width = 0, height = 0;
  uint32_t frameIndex = 0;  // the frame's index in the capture: noise depends on it, nothing else
};

// What a capture carries besides depth (identical in every frame).
struct CaptureLayout {
  bool normals = false;
  bool depth2 = false;
};

}  // namespace aor
