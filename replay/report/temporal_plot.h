#pragma once
// Plots of a run's temporal metrics, drawn from report.json (so they show exactly what it says):
//   temporal.svg           per frame: warping error (flicker), derivative error, abs error, with
//                          vertical markers where history was reset;
//   temporal_response.svg  abs error of disoccluded pixels by frames since disocclusion, next to
//                          what the EMA blend predicts for a full ghost (settled + excess0 * w^n).
#include <filesystem>

#include <nlohmann/json.hpp>

namespace aor {

// Writes the plots that have data; nothing for runs with fewer than 2 frames.
// `noHistoryReason` (ReplayResult::noHistoryReason): resets of that reason are not marked.
void writeTemporalPlots(const std::filesystem::path& outDir, const nlohmann::json& report, const std::string& noHistoryReason);

}  // namespace aor
