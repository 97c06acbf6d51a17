#include "report/compare.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include <fmt/format.h>

#include "core/input_error.h"
#include "core/pass_names.h"
#include "core/json_input.h"
#include "core/plain_text.h"
#include "core/compare_stats.h"
#include "report/compare_counts.h"
#include "run/gpu_total.h"

namespace aor {
namespace fs = std::filesystem;

namespace {

nlohmann::json readJsonFile(const fs::path& path) {
  // A report.json of 10^5 frames is well under 256 MiB; no array of samples is that long.
  return readBoundedJson(path, JsonLimits{std::uint64_t(256) << 20, 10'000'000, 128});
}

// What a value is, for "got ..." in a message, without echoing a long string or a whole array.
std::string briefly(const nlohmann::json& value) {
  if (value.is_number()) return value.dump();
  if (value.is_string()) return quoteForMessage(value.get_ref<const std::string&>());
  return value.type_name();
}

double positiveNumber(const nlohmann::json& value, const fs::path& path, const std::string& field) {
  if (!value.is_number() || !(value.get<double>() > 0) || !std::isfinite(value.get<double>()))
    throw InputError(path.string(), std::nullopt, field, fmt::format("must be a positive number, got {}", briefly(value)));
  return value.get<double>();
}

// Member `key` of `object`, `fallback` when it is absent; InputError naming the field when it has
// another type (nlohmann's value() would throw its own type_error).
template <typename T>
T memberOr(const nlohmann::json& object, const char* key, const T& fallback, const fs::path& path,
           const std::string& prefix) {
  auto it = object.find(key);
  if (it == object.end()) return fallback;
  const bool right = std::is_same_v<T, bool> ? it->is_boolean() : it->is_string();
  if (!right)
    throw InputError(path.string(), std::nullopt, prefix.empty() ? key : prefix + "." + key,
                     fmt::format("must be {}, got {}", std::is_same_v<T, bool> ? "true or false" : "a string", briefly(*it)));
  return it->get<T>();
}

// report.json's samples are frame-major over frames x repetitions: frames[j].gpu_ms_median names
// the passes frame j ran and run.repeat how many timed repetitions each had, which splits them
// back into frames, so the total is summed per repetition (report/gpu_total.h) exactly as the
// run summed it. A trimmed report without frames[] (tests/support/data) is taken as one frame when
// every pass has the same number of samples (true when every pass ran in every frame); otherwise it
// gets no total.
std::optional<std::vector<TimedFrame>> framesOfReport(const nlohmann::json& report, const TimingSamples& passes,
                                                      const fs::path& path) {
  auto fail = [&](const std::string& field, const std::string& problem) {
    return InputError(path.string(), std::nullopt, field, problem);
  };
  if (!report.contains("frames")) {
    for (const auto& series : passes)
      if (!series.hostCopy && series.samples.size() != passes.front().samples.size()) return std::nullopt;
    TimedFrame frame;
    for (const auto& series : passes) frame.push_back({series.name, series.samples});
    return std::vector<TimedFrame>{frame};
  }
  const auto& frames = report["frames"];
  if (!frames.is_array()) throw fail("frames", "not an array");
  const auto* repeat = report.contains("run") && report["run"].is_object() && report["run"].contains("repeat")
                           ? &report["run"]["repeat"] : nullptr;
  if (!repeat || !repeat->is_number_integer() || repeat->get<int64_t>() < 1)
    throw fail("run.repeat", "missing or not a whole number >= 1 (needed to split passes[].gpu_ms.samples into frames)");
  size_t repetitions = size_t(repeat->get<int64_t>());
  std::vector<size_t> used(passes.size(), 0);
  auto samplesField = [&](size_t i) { return fmt::format("passes[{}].gpu_ms.samples", i); };
  std::vector<TimedFrame> timed;
  for (size_t j = 0; j < frames.size(); ++j) {
    std::string field = fmt::format("frames[{}].gpu_ms_median", j);
    if (!frames[j].is_object() || !frames[j].contains("gpu_ms_median") || !frames[j]["gpu_ms_median"].is_object())
      throw fail(field, "missing or not an object (it names the passes the frame ran)");
    const auto& ran = frames[j]["gpu_ms_median"];
    for (const auto& item : ran.items())
      if (std::none_of(passes.begin(), passes.end(), [&](const auto& s) { return s.name == item.key(); }))
        throw fail(field + "." + item.key(), "names a pass that passes[] does not have");
    TimedFrame frame;
    for (size_t i = 0; i < passes.size(); ++i) {
      if (!ran.contains(passes[i].name)) continue;
      const auto& all = passes[i].samples;
      if (used[i] + repetitions > all.size())
        throw fail(samplesField(i), fmt::format("has {} samples, fewer than frames[] and run.repeat ({}) say it ran",
                                                all.size(), repetitions));
      auto first = all.begin() + std::ptrdiff_t(used[i]);
      frame.push_back({passes[i].name, std::vector<double>(first, first + std::ptrdiff_t(repetitions))});
      used[i] += repetitions;
    }
    timed.push_back(std::move(frame));
  }
  for (size_t i = 0; i < passes.size(); ++i)
    if (used[i] != passes[i].samples.size())
      throw fail(samplesField(i), fmt::format("has {} samples; frames[] and run.repeat ({}) say it ran {} times",
                                              passes[i].samples.size(), repetitions, used[i]));
  return timed;
}

// The total: the run's per-repetition sums of the compute passes and, as the run's one value,
// their median (totalMedianMs, the report's gpu_ms_total_median). Not added for a single compute
// pass, which it would only repeat.
void addTotal(TimingSamples& samples, const std::vector<TimedFrame>& frames) {
  size_t compute = std::count_if(samples.begin(), samples.end(), [](const auto& s) { return !s.hostCopy; });
  if (compute < 2) return;
  samples.push_back({"total", repetitionSumsMs(frames, PassGroup::Compute), false, totalMedianMs(frames, PassGroup::Compute)});
}

TimingSamples fromReport(const nlohmann::json& report, const fs::path& path) {
  if (!report.contains("passes") || !report["passes"].is_array())
    throw InputError(path.string(), std::nullopt, "passes", "missing (not a report.json of aoreplay run)");
  if (const RunMeasure measure = measureOfReport(report, path); measure.counted())
    return countedSamples(report, path, measure.name);
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
    if (values.empty()) throw InputError(path.string(), std::nullopt, field, "is empty");
    std::string name = withoutControlCharacters(pass["name"].get<std::string>(), path.string(), fmt::format("passes[{}].name", i));
    // A pass listed twice would add its samples into the total twice.
    if (std::any_of(samples.begin(), samples.end(), [&](const auto& e) { return e.name == name; }))
      throw InputError(path.string(), std::nullopt, fmt::format("passes[{}].name", i),
                       fmt::format("{} is listed twice", quoteForMessage(name)));
    samples.push_back({name, std::move(values), isHostCopyPass(name)});
  }
  if (samples.empty()) return samples;
  if (auto frames = framesOfReport(report, samples, path)) addTotal(samples, *frames);
  return samples;
}

double msPerUnit(const std::string& unit, const fs::path& path, const std::string& field) {
  if (unit == "ns") return 1e-6;
  if (unit == "us") return 1e-3;
  if (unit == "ms") return 1.0;
  if (unit == "s") return 1e3;
  throw InputError(path.string(), std::nullopt, field, fmt::format("unknown time unit {}", quoteForMessage(unit)));
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
// Counted (ao_bench --cost=...): the counter named after the measure holds each count.
TimingSamples fromBenchmark(const nlohmann::json& doc, const fs::path& path) {
  const RunMeasure measure = measureOfBenchmark(doc, path);
  TimingSamples samples;
  const auto& benchmarks = doc["benchmarks"];
  for (size_t i = 0; i < benchmarks.size(); ++i) {
    const auto& b = benchmarks[i];
    std::string prefix = fmt::format("benchmarks[{}]", i);
    if (!b.is_object()) throw InputError(path.string(), std::nullopt, prefix, "must be an object, got " + briefly(b));
    const auto member = [&](const char* key, const std::string& fallback) {
      return memberOr<std::string>(b, key, fallback, path, prefix);
    };
    if (member("run_type", "iteration") != "iteration") continue;
    if (memberOr<bool>(b, "error_occurred", false, path, prefix))
      throw InputError(path.string(), std::nullopt, prefix,
                       fmt::format("benchmark failed: {}", quoteForMessage(member("error_message", ""))));
    std::string name = withoutControlCharacters(withoutRepetitionCount(member("run_name", member("name", ""))), path.string(), prefix + ".name");
    if (name.empty()) throw InputError(path.string(), std::nullopt, prefix + ".name", "missing");
    double value = measure.counted()
                       ? positiveNumber(b.contains(measure.name) ? b[measure.name] : nlohmann::json(), path, prefix + "." + measure.name)
                       : positiveNumber(b.contains("real_time") ? b["real_time"] : nlohmann::json(), path, prefix + ".real_time") *
                             msPerUnit(member("time_unit", "ns"), path, prefix + ".time_unit");
    auto it = std::find_if(samples.begin(), samples.end(), [&](const auto& e) { return e.name == name; });
    if (it == samples.end()) it = samples.insert(samples.end(), {name, {}, isHostCopyPass(name.substr(0, name.find('/')))});
    it->samples.push_back(value);
  }
  return samples;
}

}  // namespace

double TimingSeries::runValue() const { return runMs ? *runMs : medianOf(samples); }

double PassComparison::ratio() const { return std::exp(logRatio); }

TimingSamples timingSamplesOf(const nlohmann::json& doc, const fs::path& path) {
  if (doc.is_object() && doc.contains("benchmarks") && doc["benchmarks"].is_array()) return fromBenchmark(doc, path);
  if (doc.is_object() && memberOr<std::string>(doc, "tool", "", path, "") == "aoreplay") return fromReport(doc, path);
  throw InputError(path.string(), std::nullopt, "",
                   "neither an aoreplay report.json (\"tool\": \"aoreplay\") nor Google Benchmark JSON (\"benchmarks\")");
}

TimingSamples loadTimingSamples(const fs::path& path) { return timingSamplesOf(readJsonFile(path), path); }

namespace {

// Every report.json under `folder`, in path order; hidden folders (an interrupted run's
// ".NAME.tmp-PID" staging folder) are not entered.
std::vector<fs::path> reportsUnder(const fs::path& folder) {
  std::vector<fs::path> reports;
  std::error_code ec;
  fs::recursive_directory_iterator it(folder, ec), end;
  if (ec) throw InputError(folder.string(), std::nullopt, "", fmt::format("cannot read the folder: {}", ec.message()));
  for (; it != end; it.increment(ec)) {
    if (ec) throw InputError(folder.string(), std::nullopt, "", fmt::format("cannot read the folder: {}", ec.message()));
    std::string name = it->path().filename().string();
    if (it->is_directory() && name.starts_with(".")) it.disable_recursion_pending();
    else if (name == "report.json" && it->is_regular_file()) reports.push_back(it->path());
  }
  std::sort(reports.begin(), reports.end());
  return reports;
}

}  // namespace

RunMeasure runMeasureOf(const nlohmann::json& doc, const fs::path& path) {
  if (doc.is_object() && memberOr<std::string>(doc, "tool", "", path, "") == "aoreplay") return measureOfReport(doc, path);
  if (doc.is_object() && doc.contains("benchmarks")) return measureOfBenchmark(doc, path);
  return {};
}

RunMeasure loadRunMeasure(const fs::path& path) { return runMeasureOf(readJsonFile(path), path); }

namespace {

// One run's file, read once for both its values and its measure.
RunTimings loadRun(const fs::path& path) {
  const auto doc = readJsonFile(path);
  auto samples = timingSamplesOf(doc, path);
  return {path.string(), std::move(samples), runMeasureOf(doc, path)};
}

}  // namespace

SideTimings loadSide(const fs::path& path) {
  SideTimings side{path.string(), {}};
  std::error_code ec;
  if (!fs::is_directory(path, ec)) {
    side.runs.push_back(loadRun(path));
    return side;
  }
  for (const auto& report : reportsUnder(path))
    side.runs.push_back(loadRun(report));
  if (side.runs.empty())
    throw InputError(path.string(), std::nullopt, "", "holds no report.json (a folder's runs are its report.json files, searched recursively)");
  return side;
}

SideTimings singleRun(TimingSamples samples, std::string source) {
  return SideTimings{source, {RunTimings{source, std::move(samples)}}};
}

const char* verdictText(Verdict v) {
  switch (v) {
    case Verdict::Same: return "same";
    case Verdict::Faster: return "faster";
    case Verdict::Slower: return "slower";
    case Verdict::Unknown: return "unknown";
  }
  return "?";
}

const char* levelText(Level level) {
  return level == Level::Runs ? "runs" : level == Level::Counts ? "counts" : "samples";
}

namespace {

// One name's values on one side: a value per run (Level::Runs) or every run's samples pooled.
struct NameValues {
  std::string name;
  std::vector<double> values;
  bool hostCopy = false;
};

std::vector<NameValues> valuesByName(const SideTimings& side, Level level) {
  std::vector<NameValues> names;
  for (const auto& run : side.runs)
    for (const auto& series : run.series) {
      if (series.samples.empty()) continue;
      auto it = std::find_if(names.begin(), names.end(), [&](const auto& n) { return n.name == series.name; });
      if (it == names.end()) it = names.insert(names.end(), {series.name, {}, series.hostCopy});
      if (level == Level::Runs)
        it->values.push_back(series.runValue());
      else
        it->values.insert(it->values.end(), series.samples.begin(), series.samples.end());
    }
  return names;
}

const NameValues* findName(const std::vector<NameValues>& names, const std::string& name) {
  auto it = std::find_if(names.begin(), names.end(), [&](const auto& n) { return n.name == name; });
  return it == names.end() ? nullptr : &*it;
}

std::vector<double> logsOf(const std::vector<double>& values) {
  std::vector<double> logs;
  for (double v : values) logs.push_back(std::log(v));
  return logs;
}

PassComparison measureName(const NameValues& base, const NameValues& other, const CompareOptions& options) {
  PassComparison p;
  p.name = base.name;
  p.judged = !base.hostCopy || options.judgeHostCopies;
  p.baselineCount = base.values.size();
  p.newCount = other.values.size();
  p.baselineValues = base.values;
  p.newValues = other.values;
  p.baselineMedian = medianOf(base.values);
  p.newMedian = medianOf(other.values);
  p.logRatio = std::log(p.newMedian) - std::log(p.baselineMedian);  // exactly antisymmetric in the sides
  p.baselineSpread = robustSpread(logsOf(base.values));
  p.newSpread = robustSpread(logsOf(other.values));
  p.effectFloor = std::max(std::log1p(options.minEffect), std::log1p(options.minEffectMs / p.baselineMedian));
  // Either side may be the disturbed one (compare_README.md, rule 4), so the noisier sets the bar.
  p.threshold = std::max(p.effectFloor, options.spreadMultiple * std::max(p.baselineSpread, p.newSpread));
  auto test = mannWhitneyU(base.values, other.values);
  p.pValue = test.pValue;
  p.exact = test.exact;
  p.baselineLargerShare = test.u / (double(p.baselineCount) * double(p.newCount));
  return p;
}

// Holm over the judged names; a name not judged is held to the strictest level (as if first).
void adjustPValues(std::vector<PassComparison>& passes, size_t judgedNames) {
  std::vector<double> judgedP;
  for (const auto& p : passes)
    if (p.judged) judgedP.push_back(p.pValue);
  auto adjusted = holmAdjusted(judgedP);
  size_t next = 0;
  for (auto& p : passes)
    p.pHolm = p.judged ? adjusted[next++] : std::min(1.0, p.pValue * double(std::max<size_t>(judgedNames, 1)));
}

// A significant change counts from the minimum effect when the values are runs: the test then sees
// the run-to-run variation itself. Within-run samples cannot, so there a change must also beat the
// noisier side's spread (compare_README.md, rule 4). Either way, a change the test cannot confirm
// is `unknown` only beyond the spread threshold: below it, it is within what the noise explains.
void decideVerdict(PassComparison& p, Level level, const CompareOptions& options, double strictestLevel, size_t fewest) {
  size_t fewer = std::min(p.baselineCount, p.newCount);
  bool large = std::abs(p.logRatio) >= p.threshold;
  bool counts = std::abs(p.logRatio) >= (level == Level::Runs ? p.effectFloor : p.threshold);
  if (smallestTwoSidedP(p.baselineCount, p.newCount) > strictestLevel) {
    // No outcome of this many values could be significant: neither a change nor its absence is known.
    p.verdict = Verdict::Unknown;
    p.moreNeeded = std::max(fewest, fewer + 1) - fewer;
  } else if (p.pHolm <= options.alpha && counts) {
    p.verdict = p.logRatio > 0 ? Verdict::Slower : Verdict::Faster;
  } else if (large) {
    // A big median change the test cannot confirm yet: more values will tell, so say how many.
    p.verdict = Verdict::Unknown;
    auto needed = perSideNeeded(p.baselineLargerShare, strictestLevel, std::max(fewest, std::max(p.baselineCount, p.newCount) + 1));
    if (needed) p.moreNeeded = *needed - fewer;
  } else {
    p.verdict = Verdict::Same;  // a real but small change, or no evidence of any change
  }
}

}  // namespace

Comparison compareTimings(const SideTimings& baseline, const SideTimings& candidate, const CompareOptions& options) {
  if (const std::string measure = commonMeasure(baseline, candidate); measure != "time")
    return compareCounts(baseline, candidate, measure, options);
  Comparison c;
  c.baselineSource = baseline.source;
  c.newSource = candidate.source;
  c.baselineRuns = baseline.runs.size();
  c.newRuns = candidate.runs.size();
  c.level = c.baselineRuns >= 2 && c.newRuns >= 2 ? Level::Runs : Level::Samples;
  auto base = valuesByName(baseline, c.level), other = valuesByName(candidate, c.level);
  for (const auto& n : base)
    if (!findName(other, n.name)) c.onlyInBaseline.push_back(n.name);
  for (const auto& n : other)
    if (!findName(base, n.name)) c.onlyInNew.push_back(n.name);
  for (const auto& n : base)
    if (const auto* o = findName(other, n.name)) c.passes.push_back(measureName(n, *o, options));
  c.judgedNames = size_t(std::count_if(c.passes.begin(), c.passes.end(), [](const auto& p) { return p.judged; }));
  adjustPValues(c.passes, c.judgedNames);
  // The first name Holm tests faces alpha / names: what a verdict needs at the least.
  double strictest = options.alpha / double(std::max<size_t>(c.judgedNames, 1));
  c.fewestPerSide = fewestPerSide(strictest);
  for (auto& p : c.passes) decideVerdict(p, c.level, options, strictest, c.fewestPerSide);
  return c;
}

Comparison compareTimings(const TimingSamples& baseline, const TimingSamples& candidate, const CompareOptions& options) {
  return compareTimings(singleRun(baseline), singleRun(candidate), options);
}

bool Comparison::significantSlowdown() const {
  return std::any_of(passes.begin(), passes.end(), [](const auto& p) { return p.judged && p.verdict == Verdict::Slower; });
}

bool Comparison::unknownJudged() const {
  return std::any_of(passes.begin(), passes.end(), [](const auto& p) { return p.judged && p.verdict == Verdict::Unknown; });
}

bool Comparison::fails(const CompareOptions& options) const {
  return significantSlowdown() || (options.failOnUnknown && unknownJudged());
}

namespace {

std::string plural(size_t n, const char* word) { return fmt::format("{} {}{}", n, word, n == 1 ? "" : "s"); }

const char* valueWord(Level level) { return level == Level::Runs ? "run" : "sample"; }

std::string verdictCell(const PassComparison& p, Level level) {
  std::string cell = verdictText(p.verdict);
  if (p.verdict == Verdict::Unknown)
    cell += p.moreNeeded ? fmt::format(" — need {} more {}{} a side", *p.moreNeeded, valueWord(level), *p.moreNeeded == 1 ? "" : "s")
                         : fmt::format(" — no separation: more {}s may not tell", valueWord(level));
  if (!p.judged) cell += " (host copy: not judged)";
  return cell;
}

std::string header(const Comparison& c, const CompareOptions& options) {
  std::string text = fmt::format("baseline: {} ({}); new: {} ({})\n", c.baselineSource.empty() ? "-" : c.baselineSource,
                                 plural(c.baselineRuns, "run"), c.newSource.empty() ? "-" : c.newSource,
                                 plural(c.newRuns, "run"));
  if (c.level == Level::Counts)
    text += fmt::format("values: {} counted under callgrind: a change of x{:.4g} or more either way is a "
                        "verdict, without statistics\n",
                        c.measure, 1.0 + countsMinEffect(c.measure, options));
  else if (c.level == Level::Runs)
    text += fmt::format("values: one per run (its median; the total's: its median per-repetition sum), {} a side "
                        "at the least for a verdict over {}\n",
                        c.fewestPerSide, plural(c.judgedNames, "judged name"));
  else
    text += fmt::format("values: within-run samples (a report's frames x repetitions, a benchmark's repetitions), "
                        "as a side has one run: blind to run-to-run variation; folders of {} runs a side or more "
                        "judge runs\n",
                        c.fewestPerSide);
  return text;
}

}  // namespace

std::string comparisonTable(const Comparison& c, const CompareOptions& options) {
  size_t width = 8;
  for (const auto& p : c.passes) width = std::max(width, p.name.size());
  std::string table = header(c, options);
  if (c.level == Level::Counts) return table + countsTable(c, width);
  table += fmt::format("{:<{}} {:>11} {:>11} {:>8} {:>9} {:>9} {:>9}  {}\n", "name", width, "base ms", "new ms", "ratio",
                       "threshold", "p (Holm)", "n", "verdict");
  for (const auto& p : c.passes)
    table += fmt::format("{:<{}} {:>11.4f} {:>11.4f} {:>8} {:>9} {:>9.2g} {:>4}/{:<4}  {}\n", p.name, width,
                         p.baselineMedian, p.newMedian, fmt::format("x{:.3f}", p.ratio()),
                         fmt::format("x{:.3f}", std::exp(p.threshold)), p.pHolm, p.baselineCount, p.newCount,
                         verdictCell(p, c.level));
  for (const auto& name : c.onlyInBaseline) table += fmt::format("only in baseline: {}\n", name);
  for (const auto& name : c.onlyInNew) table += fmt::format("only in new: {}\n", name);
  return table;
}

nlohmann::json comparisonJson(const Comparison& c, const CompareOptions& options) {
  nlohmann::json passes = nlohmann::json::array();
  for (const auto& p : c.passes)
    passes.push_back({{"name", p.name}, {"verdict", verdictText(p.verdict)}, {"judged", p.judged},
                      {"more_needed_per_side", p.moreNeeded ? nlohmann::json(*p.moreNeeded) : nlohmann::json()},
                      {"baseline_median_ms", p.baselineMedian}, {"new_median_ms", p.newMedian}, {"ratio", p.ratio()},
                      {"log_ratio", p.logRatio}, {"threshold_log_ratio", p.threshold},
                      {"min_effect_log_ratio", p.effectFloor},
                      {"baseline_log_spread", p.baselineSpread}, {"new_log_spread", p.newSpread},
                      {"p_value", p.pValue}, {"p_exact", p.exact}, {"p_holm", p.pHolm},
                      {"baseline_larger_share", p.baselineLargerShare},
                      {"baseline_count", p.baselineCount}, {"new_count", p.newCount},
                      {"baseline_value", p.baselineMedian}, {"new_value", p.newMedian}});
  if (c.level == Level::Counts)  // counts are not milliseconds: only the measure-neutral names
    for (auto& p : passes) p.erase("baseline_median_ms"), p.erase("new_median_ms");
  return {{"level", levelText(c.level)},
          {"measure", c.measure},
          {"baseline", {{"source", c.baselineSource}, {"runs", c.baselineRuns}}},
          {"new", {{"source", c.newSource}, {"runs", c.newRuns}}},
          {"judged_names", c.judgedNames},
          {"fewest_per_side", c.fewestPerSide},
          {"passes", passes},
          {"only_in_baseline", c.onlyInBaseline},
          {"only_in_new", c.onlyInNew},
          {"significant_slowdown", c.significantSlowdown()},
          {"unknown", c.unknownJudged()},
          {"failed", c.fails(options)},
          {"options", {{"alpha", options.alpha}, {"min_effect", options.minEffect},
                       {"min_effect_ms", options.minEffectMs}, {"spread_multiple", options.spreadMultiple},
                       {"judge_host_copies", options.judgeHostCopies}, {"fail_on_unknown", options.failOnUnknown},
                       {"min_effect_counts", c.level == Level::Counts ? nlohmann::json(countsMinEffect(c.measure, options))
                                                                       : nlohmann::json(nullptr)}}}};
}

}  // namespace aor
