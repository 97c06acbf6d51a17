#pragma once
// What `aoreplay run` prints after its pass table, read from report.json so the terminal and the
// file cannot disagree: one line for error against the reference (RMSE, SSIM, PSNR), one for
// temporal stability (warping error, still-camera noise, response frames), and the list of what it
// wrote.
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

namespace aor {

// "error vs ray-traced reference, 8 frame(s): RMSE 0.0421, SSIM 0.9123, PSNR 27.51 dB", or why there is none.
std::string errorLine(const nlohmann::json& report);
// "temporal: warping error 1.2e-05 mean (max 3.1e-05 at frame 7); still-camera noise ...; response ...".
std::string temporalLine(const nlohmann::json& report);

// Every entry under `folder`, as the user will find it after the commit: files by name, and each
// folder of numbered frames as "ao/ (8 files: NNNN.exr, NNNN.png)". Sorted, deterministic.
std::string outputListing(const std::filesystem::path& folder);

}  // namespace aor
