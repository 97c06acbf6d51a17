#include "metrics/temporal_response.h"

#include <algorithm>
#include <cmath>

namespace aor {

ResponseSummary analyzeResponse(const std::vector<double>& errors, double historyWeight) {
  ResponseSummary r;
  if (errors.empty()) return r;
  int n = int(errors.size());
  int tailStart = std::max(0, n - kSettleTail);
  for (int i = tailStart; i < n; ++i) r.settled += errors[size_t(i)];
  r.settled /= double(n - tailStart);
  r.settledReached = tailStart >= emaResponseFrames(historyWeight);
  // An exactly zero settled error (a perfect output) still needs a band to fall into.
  double band = std::max(kResponseBand * r.settled, 1e-9);
  double excess = std::abs(errors[0] - r.settled);
  if (excess > band && historyWeight > 0.0 && historyWeight < 1.0)
    r.emaFrames = int(std::ceil(std::log(band / excess) / std::log(historyWeight)));
  r.responseFrames = n;
  for (int i = 0; i < n; ++i)
    if (std::abs(errors[size_t(i)] - r.settled) <= band) {
      r.responseFrames = i;
      break;
    }
  for (double e : errors) r.ghostEnergy += std::max(0.0, e - r.settled);
  return r;
}

int emaResponseFrames(double historyWeight, double fraction) {
  if (historyWeight <= 0.0) return 0;
  int n = 0;
  for (double residual = 1.0; residual > fraction; residual *= historyWeight) ++n;
  return n;
}

std::vector<double> emaResidual(double historyWeight, int frames) {
  std::vector<double> r(size_t(std::max(frames, 0)));
  double residual = 1.0;
  for (auto& v : r) {
    v = residual;
    residual *= historyWeight;
  }
  return r;
}

}  // namespace aor
