#pragma once
// Statistics behind `aoreplay compare`: robust location/spread of timing samples and the
// Mann-Whitney U test (normal approximation with tie and continuity correction).
#include <vector>

namespace aor {

double medianOf(std::vector<double> samples);
// Median absolute deviation from the median, scaled by 1.4826 so it estimates the standard
// deviation of normal data while ignoring the odd preempted sample.
double robustSpread(const std::vector<double>& samples);

struct MannWhitney {
  double u = 0;       // U statistic of the first sample (counts pairs where a > b, ties count 1/2)
  double z = 0;       // standardised U, continuity-corrected; positive when the second sample is larger
  double pValue = 1;  // two-sided
};

// Two-sided test that a and b come from the same distribution. Ranks are midranks for ties and
// the variance carries the tie correction; with no spread at all (every value tied) p = 1.
MannWhitney mannWhitneyU(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace aor
