#pragma once
// A device's measured rates, the denominators of a pass's floor (bench/floor.h): the bandwidth of
// a large buffer copy (vkCmdCopyBuffer, bytes read plus bytes written per ms) and the rate of
// texelFetch from an R32F image in cache (fetch_rate.comp), each the median of `reps` timed runs
// after a warm-up, from timestamp queries.
#include <cstdint>
#include <utility>

#include "vk/context.h"

namespace aor::bench {

struct DeviceRates {
  double copyBytesPerMs = 0;     // read + written
  double texelFetchesPerMs = 0;
  uint64_t copyBytes = 0;        // the copied buffer's size
  std::pair<int, int> fetchSize;  // the fetch kernel's grid
};

DeviceRates measureDeviceRates(VulkanContext& vk, uint64_t copyBytes, std::pair<int, int> fetchSize, int reps,
                               double warmupMs);

}  // namespace aor::bench
