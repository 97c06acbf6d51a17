#include "bench_scaling.h"

#include <cmath>

#include <fmt/format.h>

namespace aor::bench {

LineFit fitLine(const std::vector<std::pair<double, double>>& points) {
  LineFit fit;
  double n = double(points.size());
  if (points.size() < 2) return fit;
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (auto [x, y] : points) {
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  double denominator = n * sxx - sx * sx;
  if (denominator == 0) return fit;
  fit.slope = (n * sxy - sx * sy) / denominator;
  fit.intercept = (sy - fit.slope * sx) / n;
  double meanY = sy / n, residual = 0, total = 0;
  for (auto [x, y] : points) {
    double predicted = fit.intercept + fit.slope * x;
    residual += (y - predicted) * (y - predicted);
    total += (y - meanY) * (y - meanY);
  }
  fit.r2 = total > 0 ? 1 - residual / total : 1;
  return fit;
}

void printScaling(std::FILE* out, const ScalingInput& in) {
  if (in.byPixels.size() >= 2) {
    std::vector<std::pair<double, double>> perMegapixel, logLog;
    for (auto [pixels, ms] : in.byPixels) {
      perMegapixel.push_back({pixels / 1e6, ms});
      logLog.push_back({std::log(pixels), std::log(ms)});
    }
    auto linear = fitLine(perMegapixel);
    auto power = fitLine(logLog);
    fmt::print(out, "scaling with pixels (pipeline, high): {:.4f} ms per megapixel + {:.4f} ms, R^2 {:.4f}; "
                    "log-log slope {:.3f} (1 = linear)\n", linear.slope, linear.intercept, linear.r2, power.slope);
    for (auto [pixels, ms] : in.byPixels) fmt::print(out, "  {:>10.0f} px  {:9.4f} ms\n", pixels, ms);
  }
  if (in.bySliceSteps.size() >= 2) {
    auto linear = fitLine(in.bySliceSteps);
    fmt::print(out, "scaling with slices x steps (pipeline, {}): {:.4f} ms per slice-step + {:.4f} ms, R^2 {:.4f}\n",
               in.sliceStepsSize, linear.slope, linear.intercept, linear.r2);
    for (auto [sliceSteps, ms] : in.bySliceSteps) fmt::print(out, "  {:>4.0f} slice-steps  {:9.4f} ms\n", sliceSteps, ms);
  }
}

}  // namespace aor::bench
