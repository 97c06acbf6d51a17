#pragma once
// Statistics behind `aoreplay compare`: robust location/spread of timing values, the Mann-Whitney
// U test (exact permutation distribution for small samples, ties included; the normal
// approximation only for large ones), Holm's correction over several names, and how many values a
// side a verdict needs.
#include <cstddef>
#include <optional>
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
  bool exact = false; // pValue from the exact permutation distribution (else the normal approximation)
};

// The exact distribution is used while smaller size x total size <= this (50 a side, or 10 against
// 490): its cost grows with the square of that product. Beyond, the normal approximation is used:
// at 50 a side its p-value is 1-35 % above the exact one for exact p between 1e-4 and 0.05, never
// below it (compare_test.cpp checks it at the limit), so it can only make verdicts rarer.
inline constexpr size_t kExactMannWhitneyLimit = 5000;

// Two-sided test that a and b come from the same distribution; exact or approximate by the
// sizes (kExactMannWhitneyLimit). Ranks are midranks for ties. The exact p-value is the share of
// all C(n, n1) ways to split the observed values into groups of a's and b's sizes whose rank sum is
// at least as far from its mean as the observed one: ties are part of that distribution, not
// approximated. With no spread at all (every value tied) p = 1.
MannWhitney mannWhitneyU(const std::vector<double>& a, const std::vector<double>& b);
// The same with the normal approximation whatever the sizes (tie-corrected variance, continuity
// correction).
MannWhitney mannWhitneyNormal(const std::vector<double>& a, const std::vector<double>& b);
// The same, always exact (any size: cost as described above).
MannWhitney mannWhitneyExact(const std::vector<double>& a, const std::vector<double>& b);

// The smallest two-sided exact p-value samples of these sizes can give (complete separation, no
// ties): 2 / C(n1 + n2, n1), at most 1. 5 a side: 2/252 = 0.0079.
double smallestTwoSidedP(size_t n1, size_t n2);
// The fewest values a side (equal sides) whose smallest p-value is at most `level`.
size_t fewestPerSide(double level);

// Holm's step-down adjustment: p-values in, adjusted p-values (same order) out. A name is
// significant at family-wise rate alpha when its adjusted p-value is <= alpha.
std::vector<double> holmAdjusted(const std::vector<double>& pValues);

// Values a side (equal sides) at which the observed separation would be significant at `level`:
// `superiority` is U / (n1 n2), the share of pairs where the first sample's value is larger, taken
// to stay as observed; the answer is at least `atLeast`. Empty when no size up to 100000 would do
// (no separation at all).
std::optional<size_t> perSideNeeded(double superiority, double level, size_t atLeast);

}  // namespace aor
