#pragma once
// The images report.html shows for a few frames of a run: the AO beside the reference, |error| as
// a heat map, and the change from the previous frame (flicker), each with its colour scale.
#include <optional>
#include <string>
#include <vector>

namespace aor::html {

struct FrameImages {
  int index = 0;
  int width = 0, height = 0;
  std::vector<float> ao;                        // visibility, 1 = open
  std::optional<std::vector<float>> reference;  // the capture's, where it has one
  std::vector<float> previousAo;                // the frame before, empty for the run's first
  std::vector<unsigned char> sky;               // 1 where the pixel is sky (no error shown), may be empty
};

// Which frames of [begin, end) a run keeps images of: up to `count`, spread evenly, preferring
// frames with a previous one (so the flicker image exists).
std::vector<int> framesToShow(int begin, int end, int count = 3);

// The section's HTML: one row of figures per frame, and the colour scales (shared by all frames,
// so frames compare by eye).
std::string frameImagesHtml(const std::vector<FrameImages>& frames);

}  // namespace aor::html
