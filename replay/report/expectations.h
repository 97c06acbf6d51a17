#pragma once
// `aoreplay run --expect FILE`: thresholds a user's CI holds a run to, checked against report.json,
// so a temporal-ghosting (or speed, or error) test is one line in CI.
//
// FILE is JSON: {"max": {"METRIC": limit, ...}, "min": {"METRIC": limit, ...}} (either may be left
// out). METRIC is a dotted path, looked up in three places:
//   - every frame's metrics (report frames[i].metrics.METRIC): each frame that has it is checked,
//     and a failure names the frame;
//   - the run's summary metrics (report metrics.METRIC);
//   - "gpu_ms.PASS": the per-frame median GPU ms of pass PASS, and its median over the whole run.
// Only numbers are compared. A METRIC found in none of these places is bad input: a misspelt
// threshold must not pass silently.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace aor {

struct Threshold {
  std::string metric;
  bool isMax = true;  // value must be <= limit; else >= limit
  double limit = 0;
};

struct ExpectationFailure {
  Threshold threshold;
  std::optional<int> frame;  // empty: the run's summary value
  double value = 0;
  std::string describe() const;  // "temporal.warping_error at frame 7: 0.0031 > max 0.002"
};

// Throws InputError naming the file and the offending field.
std::vector<Threshold> loadExpectations(const std::filesystem::path& file);

// Every violation, in threshold order, frames in report order. Throws InputError (naming
// `expectationsFile`) for a METRIC the report does not have anywhere.
std::vector<ExpectationFailure> checkExpectations(const std::vector<Threshold>& thresholds, const nlohmann::json& report,
                                                  const std::string& expectationsFile);

}  // namespace aor
