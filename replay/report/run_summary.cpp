#include "report/run_summary.h"

#include <algorithm>
#include <cctype>
#include <map>
#include <set>
#include <vector>

#include <fmt/format.h>

namespace aor {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

const json* child(const json& j, const char* key) {
  return j.is_object() && j.contains(key) && !j[key].is_null() ? &j[key] : nullptr;
}

std::string responseText(const json& temporal) {
  std::vector<std::string> parts;
  if (const json* d = child(temporal, "disocclusion"); d && d->contains("response_frames"))
    parts.push_back(fmt::format("{} frame(s) after disocclusion", (*d)["response_frames"].get<int>()));
  int worstReset = -1, resetFrame = -1;
  if (const json* resets = child(temporal, "resets"))
    for (const auto& r : *resets)
      if (r.contains("response_frames") && r["response_frames"].get<int>() > worstReset) {
        worstReset = r["response_frames"].get<int>();
        resetFrame = r["frame"].get<int>();
      }
  if (worstReset >= 0) parts.push_back(fmt::format("{} after the reset at frame {} (slowest)", worstReset, resetFrame));
  if (parts.empty()) return "no reset or disocclusion to recover from";
  return fmt::format("{}", fmt::join(parts, ", "));
}

// "ao/#.exr" for "ao/0007.exr": numbered frames are listed once per pattern.
std::string patternOf(const std::string& name) {
  auto dot = name.find('.');
  std::string stem = name.substr(0, dot);
  if (stem.empty() || !std::all_of(stem.begin(), stem.end(), [](unsigned char c) { return std::isdigit(c); })) return name;
  return std::string(stem.size(), 'N') + (dot == std::string::npos ? "" : name.substr(dot));
}

}  // namespace

std::string errorLine(const json& report) {
  const json* metrics = child(report, "metrics");
  const json* error = metrics ? child(*metrics, "error") : nullptr;
  if (!error) return "error: not measured (the capture has no reference for these frames; `capture --reference-spp N` makes one)";
  std::string psnr = (*error)["psnr"].is_number() ? fmt::format(", PSNR {:.2f} dB", (*error)["psnr"].get<double>()) : ", PSNR inf (identical)";
  std::string band;
  if (const json* b = child(*error, "halo_band"); b && (*b)["pixels"].get<int64_t>() > 0)
    band = fmt::format("; halo band RMSE {:.5f}, bias {:+.4f} ({} px, radius {:g})", (*b)["rmse"].get<double>(),
                       (*b)["bias"].get<double>(), (*b)["pixels"].get<int64_t>(), (*b)["radius"].get<double>());
  return fmt::format("error vs {} reference, {} frame(s): RMSE {:.5f}, SSIM {:.4f}{}{}", (*error).value("reference", "?"),
                     (*error)["frames"].get<int>(), (*error)["rmse"].get<double>(), (*error)["ssim"].get<double>(), psnr,
                     band);
}

std::string temporalLine(const json& report) {
  const json* metrics = child(report, "metrics");
  const json* temporal = metrics ? child(*metrics, "temporal") : nullptr;
  if (!temporal) return "temporal: not measured (needs 2 frames or more)";
  std::string warping = "warping error: none measured (every frame reset history)";
  if (const json* w = child(*temporal, "warping_error"))
    warping = fmt::format("warping error {:.3g} mean (max {:.3g} at frame {})", (*w)["mean"].get<double>(), (*w)["max"].get<double>(),
                          (*w)["max_frame"].get<int>());
  std::string noise = "still-camera noise: no still-camera window";
  if (const json* n = child(*temporal, "static_noise"))
    noise = fmt::format("still-camera noise {:.3g} mean, p99 {:.3g}", (*n)["mean"].get<double>(), (*n)["p99"].get<double>());
  return fmt::format("temporal: {}; {}; response {}", warping, noise, responseText(*temporal));
}

std::string outputListing(const fs::path& folder) {
  std::map<std::string, std::pair<size_t, std::set<std::string>>> folders;  // "ao" -> files, patterns
  std::set<std::string> files;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(folder, ec); !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (!it->is_regular_file()) continue;
    fs::path relative = it->path().lexically_relative(folder);
    std::string name = relative.filename().string();
    if (name.starts_with(".")) continue;  // the result marker
    if (relative.has_parent_path()) {
      auto& entry = folders[relative.parent_path().generic_string()];
      ++entry.first;
      entry.second.insert(patternOf(name));
    } else {
      files.insert(name);
    }
  }
  std::vector<std::string> items(files.begin(), files.end());
  for (const auto& [name, entry] : folders)
    items.push_back(fmt::format("{}/ ({} file(s): {})", name, entry.first, fmt::join(entry.second, ", ")));
  return fmt::format("{}", fmt::join(items, ", "));
}

}  // namespace aor
