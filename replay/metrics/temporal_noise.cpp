#include "metrics/temporal_noise.h"

#include <algorithm>
#include <cmath>

#include "core/parallel_rows.h"
#include "core/percentile.h"

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
  size_t width = size_t(geometry_.width);
  forEachRowBand(geometry_.height, [&](int firstRow, int endRow) {
    for (size_t i = size_t(firstRow) * width; i < size_t(endRow) * width; ++i) {
      double v = visibility[i];
      double delta = v - mean_[i];
      mean_[i] += delta / count_;
      m2_[i] += delta * (v - mean_[i]);
    }
  });
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
  s.p99 = nearestRankPercentile(std::move(deviations), 0.99);
  return s;
}

}  // namespace aor
