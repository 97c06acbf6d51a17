#pragma once
// What `aoreplay tune` writes (docs/tuning.md): tune.json, every error figure and the search,
// bit-identical for the same inputs on the same device; tune_times.json, the GPU times, which are
// measurements and differ run to run; and two plots.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tune/cross_validation.h"
#include "tune/tuning.h"

namespace aor {

nlohmann::json tuneJson(const TuneRun& run);
nlohmann::json tuneTimesJson(const TuneRun& run);
std::string tuneObjectiveSvg(const TuneRun& run);  // objective per evaluation and the best so far
std::string tuneErrorMsSvg(const TuneRun& run);    // every evaluation; before and after per capture
// The terminal's summary: objective before and after, training and hold-out, per capture.
std::string tuneSummary(const TuneRun& run);
// tune.json's "cross_validation": the margin, every fold's held-out objective before and after, the
// verdict and what tuned.settings.json holds ("tuned" or "defaults").
nlohmann::json crossValidationJson(const CrossValidation& cv);
// One line a fold, and the verdict.
std::string crossValidationSummary(const CrossValidation& cv, const std::string& objective);

}  // namespace aor
