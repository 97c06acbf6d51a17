#include "run/gpu_total.h"

#include <stdexcept>

#include <fmt/format.h>

#include "core/pass_names.h"
#include "core/stats.h"

namespace aor {

std::vector<double> repetitionSumsMs(const std::vector<TimedFrame>& frames, PassGroup group) {
  std::vector<double> sums;
  for (size_t f = 0; f < frames.size(); ++f) {
    std::vector<double> frameSums;
    bool first = true;
    for (const auto& pass : frames[f]) {
      if (isHostCopyPass(pass.name) != (group == PassGroup::HostCopies)) continue;
      if (first) frameSums.assign(pass.durationsMs.size(), 0.0);
      first = false;
      if (pass.durationsMs.size() != frameSums.size())
        throw std::invalid_argument(fmt::format("frame {}: pass {} has {} timed repetitions, an earlier pass {}", f,
                                                pass.name, pass.durationsMs.size(), frameSums.size()));
      for (size_t r = 0; r < frameSums.size(); ++r) frameSums[r] += pass.durationsMs[r];
    }
    sums.insert(sums.end(), frameSums.begin(), frameSums.end());
  }
  return sums;
}

double totalMedianMs(const std::vector<TimedFrame>& frames, PassGroup group) {
  return summarize(repetitionSumsMs(frames, group)).median;  // 0 for no sums
}

}  // namespace aor
