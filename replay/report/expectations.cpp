#include "report/expectations.h"

#include <sstream>

#include <fmt/format.h>

#include "core/input_error.h"
#include "core/json_input.h"

namespace aor {
namespace {

// The number at a dotted path inside `root`, if there is one.
std::optional<double> numberAt(const nlohmann::json& root, const std::string& path) {
  const nlohmann::json* node = &root;
  std::stringstream parts(path);
  std::string part;
  while (std::getline(parts, part, '.')) {
    if (!node->is_object() || !node->contains(part)) return std::nullopt;
    node = &(*node)[part];
  }
  if (!node->is_number()) return std::nullopt;
  return node->get<double>();
}

constexpr const char* kPassPrefix = "gpu_ms.";

std::optional<double> frameValue(const nlohmann::json& frame, const std::string& metric) {
  if (metric.rfind(kPassPrefix, 0) == 0) {
    auto pass = metric.substr(std::string(kPassPrefix).size());
    if (!frame.contains("gpu_ms_median") || !frame["gpu_ms_median"].contains(pass)) return std::nullopt;
    return frame["gpu_ms_median"][pass].get<double>();
  }
  if (!frame.contains("metrics")) return std::nullopt;
  return numberAt(frame["metrics"], metric);
}

std::optional<double> summaryValue(const nlohmann::json& report, const std::string& metric) {
  if (metric.rfind(kPassPrefix, 0) == 0) {
    auto pass = metric.substr(std::string(kPassPrefix).size());
    for (const auto& p : report.value("passes", nlohmann::json::array()))
      if (p.value("name", "") == pass) return numberAt(p, "gpu_ms.median");
    return std::nullopt;
  }
  if (!report.contains("metrics")) return std::nullopt;
  return numberAt(report["metrics"], metric);
}

bool violates(const Threshold& t, double value) { return t.isMax ? !(value <= t.limit) : !(value >= t.limit); }

}  // namespace

std::string ExpectationFailure::describe() const {
  return fmt::format("{} {}: {:.6g} {} {} {:.6g}", threshold.metric, frame ? fmt::format("at frame {}", *frame) : "over the run",
                     value, threshold.isMax ? ">" : "<", threshold.isMax ? "max" : "min", threshold.limit);
}

std::vector<Threshold> loadExpectations(const std::filesystem::path& file) {
  // A thresholds file is small: 1 MiB, and no more thresholds than that could hold.
  const nlohmann::json j = readBoundedJson(file, JsonLimits{std::uint64_t(1) << 20, 10'000, 128});
  if (!j.is_object()) throw InputError(file.string(), std::nullopt, "", R"(must be an object {"max": {...}, "min": {...}})");
  std::vector<Threshold> thresholds;
  for (const auto& [bound, limits] : j.items()) {
    if (bound != "max" && bound != "min")
      throw InputError(file.string(), std::nullopt, bound, "unknown key (expected \"max\" or \"min\")");
    if (!limits.is_object()) throw InputError(file.string(), std::nullopt, bound, "must be an object METRIC -> number");
    for (const auto& [metric, limit] : limits.items()) {
      if (!limit.is_number())
        throw InputError(file.string(), std::nullopt, bound + "." + metric,
                         fmt::format("must be a number, got {}", limit.is_string()
                                                                    ? quoteForMessage(limit.get_ref<const std::string&>())
                                                                    : std::string(limit.type_name())));
      thresholds.push_back({metric, bound == "max", limit.get<double>()});
    }
  }
  if (thresholds.empty()) throw InputError(file.string(), std::nullopt, "", "holds no thresholds");
  return thresholds;
}

std::vector<ExpectationFailure> checkExpectations(const std::vector<Threshold>& thresholds, const nlohmann::json& report,
                                                  const std::string& expectationsFile) {
  std::vector<ExpectationFailure> failures;
  for (const auto& t : thresholds) {
    bool found = false;
    for (const auto& frame : report.value("frames", nlohmann::json::array())) {
      auto value = frameValue(frame, t.metric);
      if (!value) continue;
      found = true;
      if (violates(t, *value)) failures.push_back({t, frame["index"].get<int>(), *value});
    }
    if (auto value = summaryValue(report, t.metric)) {
      found = true;
      if (violates(t, *value)) failures.push_back({t, std::nullopt, *value});
    }
    if (!found)
      throw InputError(expectationsFile, std::nullopt, std::string(t.isMax ? "max." : "min.") + t.metric,
                       "this run's report has no such metric (per frame metrics.*, summary metrics.*, or gpu_ms.PASS)");
  }
  return failures;
}

}  // namespace aor
