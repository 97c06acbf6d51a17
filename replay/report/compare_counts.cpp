#include "report/compare_counts.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/compare_stats.h"
#include "core/pass_names.h"
#include "core/input_error.h"
#include "core/json_input.h"

namespace aor {
namespace fs = std::filesystem;

namespace {

InputError bad(const fs::path& path, const std::string& field, const std::string& problem) {
  return InputError(path.string(), std::nullopt, field, problem);
}

std::vector<double> positiveNumbers(const nlohmann::json& values, const fs::path& path, const std::string& field) {
  if (!values.is_array() || values.empty()) throw bad(path, field, "must be a non-empty array of counts");
  std::vector<double> out;
  for (size_t k = 0; k < values.size(); ++k) {
    const auto& v = values[k];
    if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() <= 0)
      throw bad(path, fmt::format("{}[{}]", field, k), "must be a positive number");
    out.push_back(v.get<double>());
  }
  return out;
}

double sumOf(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s;
}

// The per-frame sums of the compute passes (every pass has one value a frame).
std::vector<double> computeSums(const TimingSamples& samples, const fs::path& path) {
  std::vector<double> sums;
  for (const auto& s : samples) {
    if (s.hostCopy) continue;
    if (sums.empty()) sums.assign(s.samples.size(), 0.0);
    if (s.samples.size() != sums.size())
      throw bad(path, "passes", fmt::format("{} has {} frames of counts, another pass {}", s.name, s.samples.size(), sums.size()));
    for (size_t i = 0; i < sums.size(); ++i) sums[i] += s.samples[i];
  }
  return sums;
}

std::string dependencyKey(const RunMeasure& m) { return m.dependencies.value("key", std::string()); }

// The first dependency whose value differs, for the message.
std::string firstDifference(const nlohmann::json& a, const nlohmann::json& b) {
  for (const auto& [key, value] : a.items())
    if (key != "key" && (!b.contains(key) || b[key] != value))
      return fmt::format("{} ({} against {})", key, value.dump(), b.contains(key) ? b[key].dump() : "none");
  return "the dependency key";
}

Verdict verdictOf(double ratio, double minEffect) {
  if (ratio >= 1.0 + minEffect) return Verdict::Slower;
  if (ratio <= 1.0 / (1.0 + minEffect)) return Verdict::Faster;
  return Verdict::Same;
}

std::vector<std::pair<std::string, std::pair<bool, std::vector<double>>>> runValues(const SideTimings& side) {
  std::vector<std::pair<std::string, std::pair<bool, std::vector<double>>>> names;
  for (const auto& run : side.runs)
    for (const auto& s : run.series) {
      auto it = std::find_if(names.begin(), names.end(), [&](const auto& n) { return n.first == s.name; });
      if (it == names.end()) it = names.insert(names.end(), {s.name, {s.hostCopy, {}}});
      it->second.second.push_back(s.runValue());
    }
  return names;
}

}  // namespace

double countsMinEffect(const std::string& measure) { return measure == "cycles" ? 0.01 : 0.001; }

double countsMinEffect(const std::string& measure, const CompareOptions& options) {
  return options.minEffectCounts.value_or(countsMinEffect(measure));
}

RunMeasure measureOfReport(const nlohmann::json& report, const fs::path& path) {
  RunMeasure m;
  if (!report.contains("cost")) return m;
  const auto& cost = report["cost"];
  if (!cost.is_object() || !cost.contains("measure") || !cost["measure"].is_string())
    throw bad(path, "cost.measure", "missing or not a string");
  m.name = cost["measure"].get<std::string>();
  if (m.name != "time" && m.name != "instructions" && m.name != "cycles")
    throw bad(path, "cost.measure", fmt::format("must be time, instructions or cycles, got {}", quoteForMessage(m.name)));
  if (m.counted()) m.dependencies = cost;
  return m;
}

RunMeasure measureOfBenchmark(const nlohmann::json& doc, const fs::path& path) {
  if (!doc.contains("context") || !doc["context"].is_object() || !doc["context"].contains("aoreplay_cost")) return {};
  const auto& text = doc["context"]["aoreplay_cost"];
  nlohmann::json cost = text.is_string() ? nlohmann::json::parse(text.get<std::string>(), nullptr, false) : nlohmann::json();
  if (!cost.is_object()) throw bad(path, "context.aoreplay_cost", "must be a string holding ao_bench's JSON cost block");
  RunMeasure m = measureOfReport(nlohmann::json{{"cost", cost}}, path);
  if (!m.counted()) throw bad(path, "context.aoreplay_cost.measure", "must be instructions or cycles");
  return m;
}

TimingSamples countedSamples(const nlohmann::json& report, const fs::path& path, const std::string& measure) {
  TimingSamples samples;
  for (size_t i = 0; i < report["passes"].size(); ++i) {
    const auto& pass = report["passes"][i];
    if (!pass.contains("name") || !pass["name"].is_string())
      throw bad(path, fmt::format("passes[{}].name", i), "missing or not a string");
    const std::string field = fmt::format("passes[{}].{}.per_frame", i, measure);
    if (!pass.contains(measure) || !pass[measure].is_object() || !pass[measure].contains("per_frame"))
      throw bad(path, field, "missing");
    std::vector<double> perFrame = positiveNumbers(pass[measure]["per_frame"], path, field);
    const std::string name = pass["name"].get<std::string>();
    const double total = sumOf(perFrame);
    samples.push_back({name, std::move(perFrame), isHostCopyPass(name), total});
  }
  const size_t compute = size_t(std::count_if(samples.begin(), samples.end(), [](const auto& s) { return !s.hostCopy; }));
  if (compute >= 2) {
    std::vector<double> sums = computeSums(samples, path);
    const double total = sumOf(sums);
    samples.push_back({"total", std::move(sums), false, total});
  }
  return samples;
}

std::string commonMeasure(const SideTimings& baseline, const SideTimings& candidate) {
  const RunTimings* first = nullptr;
  for (const SideTimings* side : {&baseline, &candidate})
    for (const auto& run : side->runs) {
      if (!first) {
        first = &run;
        continue;
      }
      if (run.measure.name != first->measure.name)
        throw InputError(run.source, std::nullopt, "cost.measure",
                         fmt::format("measures {}, {} measures {}: a comparison needs one measure", run.measure.name,
                                     first->source, first->measure.name));
      if (run.measure.counted() && dependencyKey(run.measure) != dependencyKey(first->measure))
        throw InputError(run.source, std::nullopt, "cost",
                         fmt::format("its counts depend on other things than {}'s: {}; counts compare only on the "
                                     "same device, driver, CPU model and valgrind",
                                     first->source, firstDifference(run.measure.dependencies, first->measure.dependencies)));
    }
  return first ? first->measure.name : "time";
}

Comparison compareCounts(const SideTimings& baseline, const SideTimings& candidate, const std::string& measure,
                         const CompareOptions& options) {
  Comparison c;
  c.level = Level::Counts;
  c.measure = measure;
  c.baselineSource = baseline.source;
  c.newSource = candidate.source;
  c.baselineRuns = baseline.runs.size();
  c.newRuns = candidate.runs.size();
  c.fewestPerSide = 1;
  const auto base = runValues(baseline), other = runValues(candidate);
  auto find = [](const auto& names, const std::string& name) {
    return std::find_if(names.begin(), names.end(), [&](const auto& n) { return n.first == name; });
  };
  for (const auto& n : base)
    if (find(other, n.first) == other.end()) c.onlyInBaseline.push_back(n.first);
  for (const auto& n : other)
    if (find(base, n.first) == base.end()) c.onlyInNew.push_back(n.first);
  for (const auto& [name, values] : base) {
    auto o = find(other, name);
    if (o == other.end()) continue;
    PassComparison p;
    p.name = name;
    p.judged = !values.first || options.judgeHostCopies;
    p.baselineValues = values.second;
    p.newValues = o->second.second;
    p.baselineCount = p.baselineValues.size();
    p.newCount = p.newValues.size();
    p.baselineMedian = medianOf(p.baselineValues);  // the runs agree when counts are exact
    p.newMedian = medianOf(p.newValues);
    p.logRatio = std::log(p.newMedian) - std::log(p.baselineMedian);
    const double minEffect = countsMinEffect(measure, options);
    p.effectFloor = p.threshold = std::log1p(minEffect);
    p.pValue = p.pHolm = std::abs(p.logRatio) >= p.threshold ? 0.0 : 1.0;
    p.exact = true;
    p.verdict = verdictOf(p.ratio(), minEffect);
    c.passes.push_back(std::move(p));
  }
  c.judgedNames = size_t(std::count_if(c.passes.begin(), c.passes.end(), [](const auto& p) { return p.judged; }));
  return c;
}

std::string countsTable(const Comparison& c, size_t width) {
  std::string table = fmt::format("{:<{}} {:>16} {:>16} {:>10}  {}\n", "name", width, "base", "new", "ratio", "verdict");
  for (const auto& p : c.passes)
    table += fmt::format("{:<{}} {:>16.0f} {:>16.0f} {:>10}  {}{}\n", p.name, width, p.baselineMedian, p.newMedian,
                         fmt::format("x{:.5f}", p.ratio()), verdictText(p.verdict),
                         p.judged ? "" : " (host copy: not judged)");
  for (const auto& name : c.onlyInBaseline) table += fmt::format("only in baseline: {}\n", name);
  for (const auto& name : c.onlyInNew) table += fmt::format("only in new: {}\n", name);
  return table;
}

}  // namespace aor
