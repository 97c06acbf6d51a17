#include "run/counted.h"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

#include <fmt/format.h>

#include "core/input_error.h"

namespace aor {

void prepareCountedReplay(CostMeasure cost, const TimedOnlyOptions& given, ReplayOptions& options) {
  const char* measure = costMeasureName(cost);
  if (given.repeat != 1)
    throw InputError("", std::nullopt, "--repeat",
                     fmt::format("--cost {} counts one run a frame (counts do not vary): --repeat must be 1", measure));
  if (given.overlap)
    throw InputError("", std::nullopt, "--overlap",
                     fmt::format("--cost {} counts the device's thread while the tool waits: its workers must not run "
                                 "meanwhile, so --overlap is refused",
                                 measure));
  if (given.validate)
    throw InputError("", std::nullopt, "--validate",
                     fmt::format("--cost {}: validate with a timed run (the validation layer under valgrind takes "
                                 "minutes a frame, and its messages do not depend on the measure)",
                                 measure));
  const char* dumps = std::getenv(kCostDumpsVariable);
  if (!dumps || !*dumps) throw std::runtime_error(std::string(kCostDumpsVariable) + " is not set under callgrind");
  options.cost = cost;
  options.costDumps = dumps;
  options.timingMode = TimingMode::Isolated;
  options.warmup = std::max(options.warmup, 1);
}

void prepareCountedContext(VulkanContext& vk, CostMeasure cost) {
  if (cost == CostMeasure::Time) return;
  if (!vk.info.isLavapipe)
    throw InputError("", std::nullopt, "--device",
                     fmt::format("--cost {} counts lavapipe's work on this CPU; device '{}' ({}) is not lavapipe",
                                 costMeasureName(cost), vk.info.name, vk.info.driver));
  vk.settleAfterSubmit = true;
}

}  // namespace aor
