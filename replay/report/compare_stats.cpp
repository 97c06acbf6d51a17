#include "report/compare_stats.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace aor {

double medianOf(std::vector<double> samples) {
  if (samples.empty()) throw std::invalid_argument("median of no samples");
  size_t n = samples.size();
  std::nth_element(samples.begin(), samples.begin() + std::ptrdiff_t(n / 2), samples.end());
  double upper = samples[n / 2];
  if (n % 2) return upper;
  double lower = *std::max_element(samples.begin(), samples.begin() + std::ptrdiff_t(n / 2));
  return 0.5 * (lower + upper);
}

double robustSpread(const std::vector<double>& samples) {
  double median = medianOf(samples);
  std::vector<double> deviations;
  deviations.reserve(samples.size());
  for (double s : samples) deviations.push_back(std::abs(s - median));
  return 1.4826 * medianOf(deviations);
}

MannWhitney mannWhitneyU(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.empty() || b.empty()) throw std::invalid_argument("Mann-Whitney U needs samples on both sides");
  struct Tagged {
    double value;
    bool fromA;
  };
  std::vector<Tagged> all;
  for (double v : a) all.push_back({v, true});
  for (double v : b) all.push_back({v, false});
  std::sort(all.begin(), all.end(), [](const Tagged& x, const Tagged& y) { return x.value < y.value; });

  // Midranks (1-based) over runs of equal values; sum t^3 - t over those runs for the variance.
  double rankSumA = 0, tieTerm = 0;
  for (size_t i = 0; i < all.size();) {
    size_t j = i;
    while (j < all.size() && all[j].value == all[i].value) ++j;
    double midrank = 0.5 * double(i + 1 + j);
    double t = double(j - i);
    tieTerm += t * t * t - t;
    for (size_t k = i; k < j; ++k)
      if (all[k].fromA) rankSumA += midrank;
    i = j;
  }
  double n1 = double(a.size()), n2 = double(b.size()), n = n1 + n2;
  MannWhitney result;
  result.u = rankSumA - n1 * (n1 + 1) / 2;
  double mean = n1 * n2 / 2;
  double variance = n1 * n2 / 12 * ((n + 1) - tieTerm / (n * (n - 1)));
  if (!(variance > 0)) return result;  // every value tied: no evidence of any difference
  // U counts pairs where a wins; b larger means U below its mean, reported as positive z.
  double difference = mean - result.u;
  double corrected = std::max(0.0, std::abs(difference) - 0.5);
  result.z = std::copysign(corrected / std::sqrt(variance), difference);
  result.pValue = std::min(1.0, std::erfc(std::abs(result.z) / std::sqrt(2.0)));
  return result;
}

}  // namespace aor
