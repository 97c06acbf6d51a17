#pragma once
// The Hodges-Lehmann estimate of the shift between two samples and its distribution-free
// confidence interval (Moses), the companions of the Mann-Whitney U test (core/compare_stats.h,
// which the trend's test itself uses).
#include <cstddef>
#include <vector>

namespace aor::results {

struct ShiftEstimate {
  double shift = 0;          // median of all differences after - before
  double lower = 0, upper = 0;  // confidence interval of the shift
  double confidence = 0;     // its actual coverage (exact, >= the asked one unless the sizes cannot reach it)
};

// `before` and `after` non-empty; `confidence` in (0, 1). The interval is [D(c), D(mn + 1 - c)] of
// the m n sorted differences D, c the largest whole number with P(U < c) <= (1 - confidence) / 2
// under U's exact null distribution (no ties); when even c = 1 cannot reach it, c = 1 and
// `confidence` says what it is.
ShiftEstimate hodgesLehmann(const std::vector<double>& before, const std::vector<double>& after, double confidence);

// P(U <= u) for U the Mann-Whitney count of pairs (x from a sample of m, y from one of n) with
// x < y, under the null hypothesis without ties: its exact distribution.
std::vector<double> mannWhitneyNullCdf(size_t m, size_t n);

}  // namespace aor::results
