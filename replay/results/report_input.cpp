#include "results/report_input.h"

#include <fmt/format.h>

#include "core/sha256.h"
#include "core/input_error.h"
#include "core/json_input.h"
#include "core/plain_text.h"

namespace aor::results {
namespace fs = std::filesystem;

std::string SeriesKey::fingerprint() const {
  nlohmann::json key{{"capture_sha256", captureSha256}, {"technique", technique}, {"settings", settings},
                     {"frames", frames},                {"timing_mode", timingMode}, {"device", device},
                     {"driver", driver},                {"tool_version", toolVersion}};
  if (counted()) key["measure"] = measure, key["cost_key"] = costKey;
  return textSha256(key.dump());  // nlohmann writes keys sorted: the same text on every machine
}

std::string SeriesKey::label() const {
  return fmt::format("{} {} on {}{}", captureName, technique, device, counted() ? " (" + measure + ")" : "");
}

namespace {

const nlohmann::json& member(const nlohmann::json& object, const std::string& path, const fs::path& file) {
  const nlohmann::json* at = &object;
  size_t start = 0;
  while (true) {
    size_t dot = path.find('.', start);
    std::string key = path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    if (!at->is_object() || !at->contains(key))
      throw InputError(file.string(), std::nullopt, path,
                       "missing (record needs a report.json written by this version of aoreplay run)");
    at = &(*at)[key];
    if (dot == std::string::npos) return *at;
    start = dot + 1;
  }
}

std::string text(const nlohmann::json& object, const std::string& path, const fs::path& file) {
  const auto& value = member(object, path, file);
  if (!value.is_string()) throw InputError(file.string(), std::nullopt, path, "must be a string");
  return withoutControlCharacters(value.get<std::string>(), file.string(), path);
}

}  // namespace

ReportInput readReportInput(const fs::path& path) {
  auto report = readBoundedJson(path, JsonLimits{std::uint64_t(256) << 20, 10'000'000, 128});
  if (!report.is_object() || !report.contains("tool") || report["tool"] != "aoreplay")
    throw InputError(path.string(), std::nullopt, "tool", "not an aoreplay report.json (\"tool\": \"aoreplay\")");
  ReportInput input;
  input.source = path.string();
  input.reportSha256 = fileSha256(path);
  auto& key = input.series;
  key.captureName = text(report, "capture.name", path);
  key.captureSha256 = text(report, "capture.content_sha256", path);
  const auto& settings = member(report, "settings", path);
  if (!settings.is_object()) throw InputError(path.string(), std::nullopt, "settings", "must be an object");
  key.technique = text(report, "settings.technique", path);
  key.settings = settings.dump();
  key.frames = member(report, "run.frames", path).dump();
  key.timingMode = text(report, "timing.mode", path);
  key.device = text(report, "device.name", path);
  key.driver = text(report, "device.driver", path);
  key.toolVersion = text(report, "tool_version", path);
  const RunMeasure measure = runMeasureOf(report, path);
  key.measure = measure.name;
  if (measure.counted()) key.costKey = measure.dependencies.value("key", std::string());
  input.passes = timingSamplesOf(report, path);
  if (input.passes.empty()) throw InputError(path.string(), std::nullopt, "passes", "is empty: nothing was timed");
  return input;
}

}  // namespace aor::results
