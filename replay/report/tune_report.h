#pragma once
// What `aoreplay tune` writes (README, "Tuning"): tune.json, every error figure and the search,
// bit-identical for the same inputs on the same device; tune_times.json, the GPU times, which are
// measurements and differ run to run; and two plots.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tune/tuning.h"

namespace aor {

nlohmann::json tuneJson(const TuneRun& run);
nlohmann::json tuneTimesJson(const TuneRun& run);
std::string tuneObjectiveSvg(const TuneRun& run);  // objective per evaluation and the best so far
std::string tuneErrorMsSvg(const TuneRun& run);    // every evaluation; before and after per capture
// The terminal's summary: objective before and after, training and hold-out, per capture.
std::string tuneSummary(const TuneRun& run);

}  // namespace aor
