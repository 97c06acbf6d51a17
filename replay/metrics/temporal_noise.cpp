#include "metrics/temporal_noise.h"

#include <algorithm>
#include <cmath>

namespace aor {

bool StaticWindow::continues(const FrameGeometry& g, bool cut) const {
  return count_ > 0 && !cut && g.width == geometry_.width && g.height == geometry_.height && g.view == geometry_.view &&
         g.projection == geometry_.projection;
}

void StaticWindow::start(int frame, const FrameGeometry& geometry) {
  geometry_ = geometry;
  first_ = frame;
  count_ = 0;
  mean_.assign(geometry.distance.size(), 0.0);
  m2_.assign(geometry.distance.size(), 0.0);
}

void StaticWindow::add(const float* visibility) {
  ++count_;
  for (size_t i = 0; i < mean_.size(); ++i) {
    double v = visibility[i];
    double delta = v - mean_[i];
    mean_[i] += delta / count_;
    m2_[i] += delta * (v - mean_[i]);
  }
}

std::vector<float> StaticWindow::pixelDeviations() const {
  std::vector<float> deviations;
  if (count_ < kMinStaticFrames) return deviations;
  for (size_t i = 0; i < mean_.size(); ++i)
    if (!geometry_.isSky(i)) deviations.push_back(float(std::sqrt(std::max(0.0, m2_[i] / count_))));
  return deviations;
}

NoiseSummary summarizeNoise(std::vector<float> deviations) {
  NoiseSummary s;
  s.pixels = deviations.size();
  if (deviations.empty()) return s;
  double sum = 0;
  for (float d : deviations) sum += d;
  s.mean = sum / double(deviations.size());
  size_t rank = size_t(std::ceil(0.99 * double(deviations.size())));
  rank = std::clamp<size_t>(rank, 1, deviations.size()) - 1;
  std::nth_element(deviations.begin(), deviations.begin() + std::ptrdiff_t(rank), deviations.end());
  s.p99 = deviations[rank];
  return s;
}

}  // namespace aor
