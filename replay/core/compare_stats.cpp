#include "core/compare_stats.h"

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

namespace {

// The pooled values sorted, as groups of equal values: how many of each sample, and the group's
// doubled midrank (an integer: first rank + last rank, 1-based).
struct TieGroup {
  size_t fromA = 0, fromB = 0;
  size_t doubledRank = 0;
  size_t size() const { return fromA + fromB; }
};

std::vector<TieGroup> tieGroups(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.empty() || b.empty()) throw std::invalid_argument("Mann-Whitney U needs samples on both sides");
  std::vector<std::pair<double, bool>> all;  // value, from a
  for (double v : a) all.emplace_back(v, true);
  for (double v : b) all.emplace_back(v, false);
  std::sort(all.begin(), all.end());
  std::vector<TieGroup> groups;
  for (size_t i = 0; i < all.size();) {
    TieGroup g;
    size_t j = i;
    for (; j < all.size() && all[j].first == all[i].first; ++j) (all[j].second ? g.fromA : g.fromB)++;
    g.doubledRank = (i + 1) + j;
    groups.push_back(g);
    i = j;
  }
  return groups;
}

double doubledRankSumOfA(const std::vector<TieGroup>& groups) {
  double sum = 0;
  for (const auto& g : groups) sum += double(g.fromA) * double(g.doubledRank);
  return sum;
}

double choose(size_t n, size_t k) {
  double c = 1;
  for (size_t i = 1; i <= k; ++i) c = c * double(n - k + i) / double(i);
  return c;
}

MannWhitney withU(const std::vector<TieGroup>& groups, size_t n1) {
  MannWhitney r;
  r.u = doubledRankSumOfA(groups) / 2 - double(n1) * double(n1 + 1) / 2;
  return r;
}

}  // namespace

MannWhitney mannWhitneyNormal(const std::vector<double>& a, const std::vector<double>& b) {
  auto groups = tieGroups(a, b);
  MannWhitney result = withU(groups, a.size());
  double tieTerm = 0;
  for (const auto& g : groups) {
    double t = double(g.size());
    tieTerm += t * t * t - t;
  }
  double n1 = double(a.size()), n2 = double(b.size()), n = n1 + n2;
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

MannWhitney mannWhitneyExact(const std::vector<double>& a, const std::vector<double>& b) {
  auto groups = tieGroups(a, b);
  MannWhitney result = mannWhitneyNormal(a, b);  // for u and z
  result.exact = true;
  // Count the splits by the smaller side: ways[k][s] = number of ways to pick k of the values seen
  // so far (a group of t ties contributes C(t, j) ways of picking j of them) with doubled rank sum s.
  bool byA = a.size() <= b.size();
  size_t m = byA ? a.size() : b.size(), n = a.size() + b.size();
  size_t maxSum = 0;
  for (size_t r = n - m + 1; r <= n; ++r) maxSum += 2 * r;
  std::vector<double> ways((m + 1) * (maxSum + 1), 0.0);
  auto at = [&](size_t k, size_t s) -> double& { return ways[k * (maxSum + 1) + s]; };
  at(0, 0) = 1;
  size_t seen = 0;
  double observed = 0;
  for (const auto& g : groups) {
    observed += double(byA ? g.fromA : g.fromB) * double(g.doubledRank);
    size_t t = g.size();
    seen += t;
    for (size_t k = std::min(m, seen); k >= 1; --k) {  // descending: ways[k - j] still hold the earlier groups
      // k of the first `seen` values sum to at most their k largest ranks, doubled (midranks of a
      // partly picked group are never above the group's largest ranks).
      size_t reachable = std::min(maxSum, k * (2 * seen - k + 1));
      for (size_t j = 1; j <= std::min(t, k); ++j) {
        double c = choose(t, j);
        size_t shift = j * g.doubledRank;
        for (size_t s = shift; s <= reachable; ++s)
          if (double w = at(k - j, s - shift); w != 0) at(k, s) += c * w;
      }
    }
  }
  // Two-sided: every split whose rank sum is at least as far from the mean as the observed one.
  // Doubled sums are integers, so the comparison is exact.
  double mean = double(m) * double(n + 1), distance = std::abs(observed - mean), extreme = 0, all = 0;
  for (size_t s = 0; s <= maxSum; ++s) {
    all += at(m, s);
    if (std::abs(double(s) - mean) >= distance) extreme += at(m, s);
  }
  result.pValue = std::min(1.0, extreme / all);
  return result;
}

MannWhitney mannWhitneyU(const std::vector<double>& a, const std::vector<double>& b) {
  size_t smaller = std::min(a.size(), b.size()), total = a.size() + b.size();
  return smaller * total <= kExactMannWhitneyLimit ? mannWhitneyExact(a, b) : mannWhitneyNormal(a, b);
}

double smallestTwoSidedP(size_t n1, size_t n2) { return std::min(1.0, 2.0 / choose(n1 + n2, std::min(n1, n2))); }

size_t fewestPerSide(double level) {
  size_t n = 1;
  while (smallestTwoSidedP(n, n) > level) ++n;
  return n;
}

std::vector<double> holmAdjusted(const std::vector<double>& pValues) {
  std::vector<size_t> order(pValues.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](size_t x, size_t y) { return pValues[x] < pValues[y]; });
  std::vector<double> adjusted(pValues.size());
  double running = 0;  // step-down: an adjusted p-value is never below an earlier (smaller) one's
  for (size_t rank = 0; rank < order.size(); ++rank) {
    running = std::max(running, std::min(1.0, double(order.size() - rank) * pValues[order[rank]]));
    adjusted[order[rank]] = running;
  }
  return adjusted;
}

std::optional<size_t> perSideNeeded(double superiority, double level, size_t atLeast) {
  double separation = std::abs(superiority - 0.5);
  for (size_t n = std::max<size_t>(atLeast, 1); n <= 100000; n += 1 + n / 64) {
    // U's mean is n^2/2 and its variance n^2 (2n + 1) / 12 for n a side, and U - mean is n^2 x separation.
    double z = double(n) * separation * std::sqrt(12.0 / double(2 * n + 1));
    if (std::erfc(z / std::sqrt(2.0)) <= level) return n;
  }
  return std::nullopt;
}

}  // namespace aor
