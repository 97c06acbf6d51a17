#pragma once
// Static-camera temporal noise: per-pixel standard deviation of the output over a window of frames
// in which the camera (view, projection, size) does not change. Pixels without a surface are left
// out (their AO is constant 1 and would dilute the mean).
#include <vector>

#include "metrics/temporal_reprojection.h"

namespace aor {

inline constexpr int kMinStaticFrames = 3;  // a standard deviation over fewer frames says little

class StaticWindow {
 public:
  // True when `geometry` continues this window (same camera and size, no cut).
  bool continues(const FrameGeometry& geometry, bool cut) const;
  void start(int frame, const FrameGeometry& geometry);
  void add(const float* visibility);  // Welford update, in double
  int firstFrame() const { return first_; }
  int frameCount() const { return count_; }
  // Population standard deviation per surface pixel (empty with fewer than kMinStaticFrames frames).
  std::vector<float> pixelDeviations() const;

 private:
  FrameGeometry geometry_;
  int first_ = -1, count_ = 0;
  std::vector<double> mean_, m2_;
};

struct NoiseSummary {
  double mean = 0, p99 = 0;
  size_t pixels = 0;
};
NoiseSummary summarizeNoise(std::vector<float> deviations);  // p99: nearest-rank percentile

}  // namespace aor
