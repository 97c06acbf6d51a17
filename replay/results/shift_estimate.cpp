#include "results/shift_estimate.h"

#include <algorithm>
#include <stdexcept>

#include "core/compare_stats.h"

namespace aor::results {

std::vector<double> mannWhitneyNullCdf(size_t m, size_t n) {
  // ways[j][u]: arrangements of i values of the first sample and j of the second with U = u,
  // built up over i (c(i, j, u) = c(i - 1, j, u - j) + c(i, j - 1, u)).
  size_t maxU = m * n;
  std::vector<std::vector<double>> previous(n + 1, std::vector<double>(maxU + 1, 0.0));
  for (size_t j = 0; j <= n; ++j) previous[j][0] = 1;  // i = 0: one arrangement, U = 0
  for (size_t i = 1; i <= m; ++i) {
    std::vector<std::vector<double>> current(n + 1, std::vector<double>(maxU + 1, 0.0));
    current[0][0] = 1;
    for (size_t j = 1; j <= n; ++j)
      for (size_t u = 0; u <= i * j; ++u)
        current[j][u] = (u >= j ? previous[j][u - j] : 0.0) + current[j - 1][u];
    previous.swap(current);
  }
  std::vector<double> cdf(maxU + 1);
  double total = 0, running = 0;
  for (double w : previous[n]) total += w;
  for (size_t u = 0; u <= maxU; ++u) cdf[u] = (running += previous[n][u]) / total;
  return cdf;
}

ShiftEstimate hodgesLehmann(const std::vector<double>& before, const std::vector<double>& after, double confidence) {
  if (before.empty() || after.empty()) throw std::invalid_argument("Hodges-Lehmann shift needs values on both sides");
  std::vector<double> differences;
  differences.reserve(before.size() * after.size());
  for (double a : after)
    for (double b : before) differences.push_back(a - b);
  std::sort(differences.begin(), differences.end());
  ShiftEstimate e;
  e.shift = medianOf(differences);
  auto cdf = mannWhitneyNullCdf(before.size(), after.size());
  double tail = (1 - confidence) / 2;
  size_t c = 0;  // largest c with P(U < c) = P(U <= c - 1) <= tail
  while (c < cdf.size() && cdf[c] <= tail) ++c;
  c = std::max<size_t>(c, 1);
  size_t count = differences.size();
  c = std::min(c, (count + 1) / 2);
  e.lower = differences[c - 1];
  e.upper = differences[count - c];
  e.confidence = 1 - 2 * cdf[c - 1];
  return e;
}

}  // namespace aor::results
