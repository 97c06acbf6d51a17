#pragma once
// A pass's floor: the least time its counted work (vk/op_counter.h) can take at a device's measured
// rates (device_rates.h), the largest of its bytes (read and written, each bound subresource once)
// over the fastest copy bandwidth, its texture-path reads (texelFetch, textureLod, gathers,
// imageLoad) over the texelFetch rate, and one empty dispatch per dispatch of the pass; and the
// table `ao_bench --floor` prints, measured / floor per pass.
#include <algorithm>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "device_rates.h"
#include "vk/op_counter.h"

namespace aor::bench {

struct PassFloor {
  std::string config;  // TECHNIQUE/PRESET/WxH, as ao_bench names it
  DispatchCounts counts;
  double bytesMs = 0, fetchMs = 0, dispatchMs = 0;
  std::optional<double> measuredMs;  // median; none when the benchmark did not run
  double floorMs() const { return std::max({bytesMs, fetchMs, dispatchMs}); }
  const char* boundBy() const {
    if (dispatchMs >= bytesMs && dispatchMs >= fetchMs) return "dispatch";
    return bytesMs >= fetchMs ? "bytes" : "fetches";
  }
};

// `rates` may be null (counts only: every time is 0).
PassFloor passFloor(const std::string& config, const DispatchCounts& counts, const DeviceRates* rates,
                    std::optional<double> measuredMs);

void printFloorTable(std::FILE* out, const std::vector<PassFloor>& rows, const DeviceRates* rates);
nlohmann::json floorJson(const std::vector<PassFloor>& rows, const DeviceRates* rates, const std::string& device);

}  // namespace aor::bench
