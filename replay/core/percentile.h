#pragma once
// Nearest-rank percentile, the one definition every report value uses (error p99, static noise
// p99, the precision study's p99): the element of 1-based rank ceil(fraction * n) in sorted order,
// found with nth_element (no full sort). 0 for an empty input.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace aor {

template <class T>
T nearestRankPercentile(std::vector<T> values, double fraction) {
  if (values.empty()) return T(0);
  size_t rank = size_t(std::ceil(fraction * double(values.size())));  // 1-based
  size_t index = std::clamp<size_t>(rank, 1, values.size()) - 1;
  std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(index), values.end());
  return values[index];
}

}  // namespace aor
