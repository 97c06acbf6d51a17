#pragma once
// Order statistics of timing samples (medians are what the report quotes: timings are noisy).
#include <cstddef>
#include <vector>

namespace aor {

struct Summary {
  double min = 0, median = 0, max = 0, mean = 0;
  size_t count = 0;
};

Summary summarize(std::vector<double> samples);

}  // namespace aor
