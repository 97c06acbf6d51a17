#pragma once
// One replayed frame as the metrics see it: the AO output next to the inputs it came from.
// Pointers are valid only during the call that receives the frame.
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace aor {

struct AnalyzedFrame {
  int index = 0;                 // frame index in the capture
  int width = 0, height = 0;
  const float* visibility = nullptr;  // width*height, the tool's final output
  const float* depth = nullptr;       // width*height depth-attachment values of the capture
  glm::mat4 view{1.0f};
  glm::mat4 projection{1.0f};
  bool cut = false;                   // capture marks a camera cut before this frame
  bool historyValid = false;          // the temporal pass blended history into this frame
  std::string resetReason;            // why not, when !historyValid
  const std::vector<float>* reference = nullptr;  // ground-truth visibility, when the capture has it
  float historyWeight = 0.0f;          // the run's `temporal` setting (EMA history weight)
  const float* noHistory = nullptr;   // this frame replayed with temporal=0, when the run made that replay
  float bandRadius = 1.0f;            // the halo band's AO radius: the capture's scene.ao_radius, else 1
};

}  // namespace aor
