#pragma once
// How GPU time grows: with pixel count (pipeline, the default preset) and with slices x steps (the
// pipeline of the first technique benchmarked that has both keys).
// Least-squares fits, printed with their slope and R^2, so "linear" is a number, not a claim.
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace aor::bench {

struct LineFit {
  double slope = 0, intercept = 0, r2 = 0;
};
LineFit fitLine(const std::vector<std::pair<double, double>>& points);

struct ScalingInput {
  std::vector<std::pair<double, double>> byPixels;      // (pixels, median pipeline ms)
  std::vector<std::pair<double, double>> bySliceSteps;  // (slices*steps, median pipeline ms)
  std::string sliceStepsSize;
};

// Linear fits in both, plus the log-log slope against pixels (1 = linear).
void printScaling(std::FILE* out, const ScalingInput& in);

}  // namespace aor::bench
