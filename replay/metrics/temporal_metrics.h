#pragma once
// Temporal stability of the AO output (issue "Temporal stability"): flicker, ghosting, history.
//
// Per frame (frames[i].metrics.temporal), sky pixels excluded everywhere:
//   warping_error      Lai et al. 2018: mean squared difference between this output and the previous
//                      output reprojected into this frame (depth + both cameras, bilinear read), over
//                      pixels that pass the disocclusion mask (on screen last frame and depth
//                      consistent within 5%: the temporal pass's own rejection layers 1 and 2).
//                      Not measured on the first frame, after a cut or a size change.
//   disoccluded_fraction  surface pixels that fail that mask.
//   derivative_error   mean |dO - dR| with dX = X_t - X_{t-1} per pixel (O output, R reference), so a
//                      real change in AO is not counted as flicker. Needs references for both frames.
//   abs_error          mean |O - R|, R = the reference, else the same frame replayed with temporal=0
//                      (error_source says which); the curve the ghosting analysis reads.
//   response_frames, ghost_energy, settled_error  on a frame where history was reset: the recovery
//                      of abs_error over the frames until the next reset (temporal_response.h).
// Summary (metrics.temporal): static-camera temporal noise (per-pixel standard deviation over
// windows of >= 3 frames with an unchanged camera; mean and p99), means and maxima of the per-frame
// values, one entry per reset, and the disocclusion curve: abs_error of pixels by the number of
// frames since they were disoccluded, with its response time and ghost energy; all compared with
// the EMA prediction w^n (w = history weight). Pixels are followed through the reprojection, and the
// curve is chained from paired per-pixel changes (age a -> a+1 over the pixels seen at both ages),
// so pixels leaving the screen or being covered again do not change the population it describes.
#include <map>
#include <memory>
#include <vector>

#include <nlohmann/json.hpp>

#include "metrics/analyzed_frame.h"
#include "metrics/temporal_noise.h"
#include "metrics/temporal_reprojection.h"

namespace aor {

inline constexpr int kMaxTrackedAge = 63;            // the disocclusion curve's last bucket
inline constexpr size_t kMinPixelsPerAge = 16;       // fewer pixels at an age end the curve

struct TemporalFrameMetrics {
  int index = 0;
  bool historyValid = false;
  std::string resetReason;
  double disoccludedFraction = -1;  // < 0: not measured
  double warpingError = -1;
  double derivativeError = -1;
  double absError = -1;
};

class TemporalAnalysis {
 public:
  void addFrame(const AnalyzedFrame& frame);
  nlohmann::json frameJson(int index) const;  // null when nothing was measured
  nlohmann::json summaryJson() const;         // null when nothing was measured

  // For plots and checks.
  NoiseSummary staticNoise() const;
  std::vector<double> disocclusionCurve() const;  // abs_error by frames since disocclusion
  std::vector<size_t> disocclusionPixels() const;  // pixels behind each point of the curve

 private:
  struct Previous {
    FrameGeometry geometry;
    std::vector<float> visibility;
    std::vector<float> reference;  // empty when the frame had none
    std::vector<int> age;          // frames since the pixel's history started, -1 sky
    std::vector<uint8_t> sinceDisocclusion;  // 1: the history started at a disocclusion (not a reset)
    std::vector<float> error;      // |output - truth| per pixel, < 0 when unknown
  };
  void trackAges(const AnalyzedFrame& frame, const FrameGeometry& geometry, const Reprojection* reprojection,
                 const float* truth, Previous& next);
  std::vector<double> resetCurve(size_t start) const;
  NoiseSummary staticNoise(const std::vector<float>& openWindowDeviations) const;

  float historyWeight_ = 0;
  std::string errorSource_;
  std::vector<TemporalFrameMetrics> frames_;
  std::unique_ptr<Previous> previous_;
  StaticWindow window_;
  std::vector<float> closedWindowDeviations_;
  std::vector<std::pair<int, int>> staticWindows_;  // [first, last] of windows long enough to count
  // Disocclusion curve: errors of freshly disoccluded pixels (age 0), and per age a >= 1 the sum of
  // each pixel's error change from age a-1 to a.
  double freshErrorSum_ = 0;
  size_t freshCount_ = 0;
  std::vector<double> stepSum_ = std::vector<double>(kMaxTrackedAge + 1, 0.0);
  std::vector<size_t> stepCount_ = std::vector<size_t>(kMaxTrackedAge + 1, 0);
};

}  // namespace aor
