#include "report/compare.h"

#include <algorithm>
#include <cmath>
#include <fstream>

#include <fmt/format.h>

#include "capture/input_error.h"
#include "blocks/pass_names.h"
#include "report/compare_stats.h"

namespace aor {
namespace fs = std::filesystem;

namespace {

nlohmann::json readJsonFile(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string(), std::nullopt, "", "cannot open the file");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(path.string(), std::nullopt, "", fmt::format("not valid JSON: {}", e.what()));
  }
}

double positiveNumber(const nlohmann::json& value, const fs::path& path, const std::string& field) {
  if (!value.is_number() || !(value.get<double>() > 0) || !std::isfinite(value.get<double>()))
    throw InputError(path.string(), std::nullopt, field, fmt::format("must be a positive number, got {}", value.dump()));
  return value.get<double>();
}

// Elementwise sum of the compute passes' samples: the frame's GPU time per run, as ao_bench's
// "pipeline" adds it up. Only meaningful when every pass ran the same number of times (same
// frames, same repetitions).
void addTotal(TimingSamples& samples) {
  std::vector<const TimingSeries*> compute;
  for (const auto& series : samples)
    if (!series.hostCopy) compute.push_back(&series);
  if (compute.size() < 2) return;
  size_t count = compute.front()->samples.size();
  for (const auto* series : compute)
    if (series->samples.size() != count) return;
  std::vector<double> total(count, 0.0);
  for (const auto* series : compute)
    for (size_t i = 0; i < count; ++i) total[i] += series->samples[i];
  samples.push_back({"total", std::move(total)});
}

TimingSamples fromReport(const nlohmann::json& report, const fs::path& path) {
  if (!report.contains("passes") || !report["passes"].is_array())
    throw InputError(path.string(), std::nullopt, "passes", "missing (not a report.json of aoreplay run)");
  TimingSamples samples;
  for (size_t i = 0; i < report["passes"].size(); ++i) {
    const auto& pass = report["passes"][i];
    std::string field = fmt::format("passes[{}].gpu_ms.samples", i);
    if (!pass.contains("name") || !pass["name"].is_string())
      throw InputError(path.string(), std::nullopt, fmt::format("passes[{}].name", i), "missing or not a string");
    if (!pass.contains("gpu_ms") || !pass["gpu_ms"].contains("samples") || !pass["gpu_ms"]["samples"].is_array())
      throw InputError(path.string(), std::nullopt, field, "missing (report written before samples were recorded?)");
    std::vector<double> values;
    const auto& raw = pass["gpu_ms"]["samples"];
    for (size_t k = 0; k < raw.size(); ++k) values.push_back(positiveNumber(raw[k], path, fmt::format("{}[{}]", field, k)));
    std::string name = pass["name"].get<std::string>();
    samples.push_back({name, std::move(values), isHostCopyPass(name)});
  }
  addTotal(samples);
  return samples;
}

double msPerUnit(const std::string& unit, const fs::path& path, const std::string& field) {
  if (unit == "ns") return 1e-6;
  if (unit == "us") return 1e-3;
  if (unit == "ms") return 1.0;
  if (unit == "s") return 1e3;
  throw InputError(path.string(), std::nullopt, field, fmt::format("unknown time unit \"{}\"", unit));
}

// Google Benchmark names a benchmark with repetitions ".../repeats:N/...": without that segment a
// baseline taken with one --reps still matches a run taken with another.
std::string withoutRepetitionCount(std::string name) {
  auto at = name.find("/repeats:");
  if (at == std::string::npos) return name;
  auto end = name.find('/', at + 1);
  return name.erase(at, end == std::string::npos ? std::string::npos : end - at);
}

// Google Benchmark JSON: every repetition is an entry with run_type "iteration"; aggregates
// (mean, median, stddev, cv) are skipped because the test needs the samples themselves.
TimingSamples fromBenchmark(const nlohmann::json& doc, const fs::path& path) {
  TimingSamples samples;
  const auto& benchmarks = doc["benchmarks"];
  for (size_t i = 0; i < benchmarks.size(); ++i) {
    const auto& b = benchmarks[i];
    std::string prefix = fmt::format("benchmarks[{}]", i);
    if (b.value("run_type", "iteration") != "iteration") continue;
    if (b.value("error_occurred", false))
      throw InputError(path.string(), std::nullopt, prefix, fmt::format("benchmark failed: {}", b.value("error_message", "")));
    std::string name = withoutRepetitionCount(b.value("run_name", b.value("name", "")));
    if (name.empty()) throw InputError(path.string(), std::nullopt, prefix + ".name", "missing");
    double scale = msPerUnit(b.value("time_unit", "ns"), path, prefix + ".time_unit");
    double value = positiveNumber(b.contains("real_time") ? b["real_time"] : nlohmann::json(), path, prefix + ".real_time") * scale;
    auto it = std::find_if(samples.begin(), samples.end(), [&](const auto& e) { return e.name == name; });
    if (it == samples.end()) it = samples.insert(samples.end(), {name, {}, isHostCopyPass(name.substr(0, name.find('/')))});
    it->samples.push_back(value);
  }
  return samples;
}

}  // namespace

TimingSamples loadTimingSamples(const fs::path& path) {
  auto doc = readJsonFile(path);
  if (doc.is_object() && doc.contains("benchmarks") && doc["benchmarks"].is_array()) return fromBenchmark(doc, path);
  if (doc.is_object() && doc.value("tool", "") == "aoreplay") return fromReport(doc, path);
  throw InputError(path.string(), std::nullopt, "",
                   "neither an aoreplay report.json (\"tool\": \"aoreplay\") nor Google Benchmark JSON (\"benchmarks\")");
}

const char* verdictText(Verdict v) {
  switch (v) {
    case Verdict::Same: return "same";
    case Verdict::Faster: return "faster";
    case Verdict::Slower: return "slower";
    case Verdict::Unknown: return "unknown — need more repetitions";
  }
  return "?";
}

Verdict decideVerdict(const PassComparison& p, const CompareOptions& options) {
  if (p.baselineCount < options.minSamples || p.newCount < options.minSamples) return Verdict::Unknown;
  bool significant = p.pValue < p.alpha;
  bool large = std::abs(p.change) >= p.threshold;
  if (significant && large) return p.change > 0 ? Verdict::Slower : Verdict::Faster;
  // A big median change the test cannot confirm yet: more samples will tell, so say so.
  if (large) return Verdict::Unknown;
  return Verdict::Same;  // a real but tiny change, or no evidence of any change
}

Comparison compareTimings(const TimingSamples& baseline, const TimingSamples& candidate, const CompareOptions& options) {
  Comparison c;
  auto find = [](const TimingSamples& s, const std::string& name) {
    return std::find_if(s.begin(), s.end(), [&](const auto& e) { return e.name == name; });
  };
  for (const auto& series : baseline)
    if (find(candidate, series.name) == candidate.end()) c.onlyInBaseline.push_back(series.name);
  for (const auto& series : candidate)
    if (find(baseline, series.name) == baseline.end()) c.onlyInNew.push_back(series.name);
  auto judged = [&](const TimingSeries& s) { return !s.hostCopy || options.judgeHostCopies; };
  // The false-alarm rate is split over the names that can fail the comparison.
  size_t judgedCount = 0;
  for (const auto& series : baseline) judgedCount += judged(series) && find(candidate, series.name) != candidate.end();
  for (const auto& series : baseline) {
    const auto& base = series.samples;
    auto other = find(candidate, series.name);
    if (other == candidate.end() || base.empty() || other->samples.empty()) continue;
    PassComparison p;
    p.name = series.name;
    p.judged = judged(series);
    p.baselineCount = base.size();
    p.newCount = other->samples.size();
    p.baselineMedian = medianOf(base);
    p.newMedian = medianOf(other->samples);
    p.change = (p.newMedian - p.baselineMedian) / p.baselineMedian;
    p.baselineSpread = robustSpread(base) / p.baselineMedian;
    p.newSpread = robustSpread(other->samples) / p.newMedian;
    // Either run may be the disturbed one (compare_README.md, rule 4), so the noisier sets the bar.
    p.threshold = std::max({options.minEffect, options.spreadMultiple * std::max(p.baselineSpread, p.newSpread),
                            options.minEffectMs / p.baselineMedian});
    p.pValue = mannWhitneyU(base, other->samples).pValue;
    p.alpha = options.alpha / double(std::max<size_t>(judgedCount, 1));
    p.verdict = decideVerdict(p, options);
    c.passes.push_back(p);
  }
  return c;
}

bool Comparison::significantSlowdown() const {
  return std::any_of(passes.begin(), passes.end(), [](const auto& p) { return p.judged && p.verdict == Verdict::Slower; });
}

std::string comparisonTable(const Comparison& c) {
  size_t width = 8;
  for (const auto& p : c.passes) width = std::max(width, p.name.size());
  std::string table = fmt::format("{:<{}} {:>11} {:>11} {:>8} {:>9} {:>9} {:>7}  {}\n", "name", width, "base ms",
                                  "new ms", "change", "threshold", "p", "n", "verdict");
  for (const auto& p : c.passes) {
    std::string verdict = verdictText(p.verdict);
    if (!p.judged) verdict += " (host copy: not judged)";
    table += fmt::format("{:<{}} {:>11.4f} {:>11.4f} {:>+7.1f}% {:>8.1f}% {:>9.2g} {:>3}/{:<3}  {}\n", p.name, width,
                         p.baselineMedian, p.newMedian, 100 * p.change, 100 * p.threshold, p.pValue, p.baselineCount,
                         p.newCount, verdict);
  }
  for (const auto& name : c.onlyInBaseline) table += fmt::format("only in baseline: {}\n", name);
  for (const auto& name : c.onlyInNew) table += fmt::format("only in new: {}\n", name);
  return table;
}

nlohmann::json comparisonJson(const Comparison& c, const CompareOptions& options) {
  nlohmann::json passes = nlohmann::json::array();
  for (const auto& p : c.passes)
    passes.push_back({{"name", p.name}, {"verdict", verdictText(p.verdict)}, {"baseline_median_ms", p.baselineMedian},
                      {"judged", p.judged}, {"new_median_ms", p.newMedian}, {"change", p.change}, {"threshold", p.threshold},
                      {"baseline_relative_spread", p.baselineSpread},
                      {"new_relative_spread", p.newSpread}, {"p_value", p.pValue}, {"alpha", p.alpha},
                      {"baseline_samples", p.baselineCount}, {"new_samples", p.newCount}});
  return {{"passes", passes},
          {"only_in_baseline", c.onlyInBaseline},
          {"only_in_new", c.onlyInNew},
          {"significant_slowdown", c.significantSlowdown()},
          {"options", {{"alpha", options.alpha}, {"min_effect", options.minEffect},
                       {"min_effect_ms", options.minEffectMs},
                       {"spread_multiple", options.spreadMultiple}, {"min_samples", options.minSamples},
                       {"judge_host_copies", options.judgeHostCopies}}}};
}

}  // namespace aor
