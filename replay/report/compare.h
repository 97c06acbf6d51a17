#pragma once
// `aoreplay compare`: per pass (or per benchmark), is the new side faster, slower or the same as
// the baseline? A side is one run or several; with several a side, each run is one value per name
// and the test sees run-to-run variation. See compare_README.md for the rules and why.
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace aor {

// One run's timing samples in milliseconds of one pass or benchmark.
struct TimingSeries {
  std::string name;
  std::vector<double> samples;
  bool hostCopy = false;          // the harness's upload or read-back (passes/pass_names.h): not judged by default
  std::optional<double> runMs;    // the run's one value; the median of `samples` when empty
  double runValue() const;
};
using TimingSamples = std::vector<TimingSeries>;  // in file order

// Reads report.json (passes[].gpu_ms.samples, plus "total": the per-repetition sums of the compute
// passes, report/gpu_total.h, whose median is the run's gpu_ms_total_median) or Google
// Benchmark JSON (iteration entries' real_time, which is the manual GPU time when the benchmark
// uses it; a name whose first segment is a host-copy pass is a host copy). Throws InputError
// naming the file and field.
TimingSamples loadTimingSamples(const std::filesystem::path& path);
// The same from a file already parsed (`path` names it in errors).
TimingSamples timingSamplesOf(const nlohmann::json& doc, const std::filesystem::path& path);

// What a run's values measure: milliseconds ("time"), or a count under callgrind ("instructions",
// "cycles") with report.json's "cost" block, which names everything the counts depend on.
struct RunMeasure {
  std::string name = "time";
  nlohmann::json dependencies;  // counted only
  bool counted() const { return name != "time"; }
};
// A run's measure: report.json's "cost" block, Google Benchmark JSON's context "aoreplay_cost"
// (ao_bench --cost=...); else time.
RunMeasure loadRunMeasure(const std::filesystem::path& path);
RunMeasure runMeasureOf(const nlohmann::json& doc, const std::filesystem::path& path);

struct RunTimings {
  std::string source;  // the file
  TimingSamples series;
  RunMeasure measure;
};
// One side of a comparison: its runs.
struct SideTimings {
  std::string source;  // what the user named: a file or a folder
  std::vector<RunTimings> runs;
};
// A file is one run (report.json or Google Benchmark JSON); a folder's runs are the report.json
// files under it, found recursively (hidden folders, such as an interrupted run's staging folder,
// are skipped), in path order. Throws InputError naming the file and field, or the folder when it
// holds no report.json.
SideTimings loadSide(const std::filesystem::path& path);
SideTimings singleRun(TimingSamples samples, std::string source = "");

struct CompareOptions {
  double alpha = 0.05;          // family-wise false-alarm rate over the judged names (Holm)
  double minEffect = 0.02;      // smallest median change worth a verdict, as a ratio (either way)
  double spreadMultiple = 2.0;  // ...and at least this many spreads (robust, of log values) of the noisier side
  double minEffectMs = 0.001;   // ...and at least this absolute change: microsecond passes shift by
                                // a fraction of a microsecond between processes (compare_README.md)
  // Counts: the smallest change that is a verdict (no statistics); unset: the measure's default
  // (countsMinEffect).
  std::optional<double> minEffectCounts;
  bool judgeHostCopies = false; // host copies vary with host memory placement from process to process
  bool failOnUnknown = false;   // a judged `unknown` fails the comparison too
};

enum class Verdict { Same, Faster, Slower, Unknown };
const char* verdictText(Verdict v);

// The default smallest change of a counted measure: instructions are exact (x1.001); cycles come
// from a cache simulation that other threads' allocations perturb by up to 9e-4 of a pass (measured,
// bench/RESULTS.md "Counted cost"), so x1.01.
double countsMinEffect(const std::string& measure);
double countsMinEffect(const std::string& measure, const CompareOptions& options);

// What the test's values are: one per run (each side has 2 runs or more), or, with a single run on
// a side, the runs' own samples (frames x repetitions), which cannot see run-to-run variation.
// Counted values are exact: one per run, judged without statistics (compare_README.md, "Counts").
enum class Level { Runs, Samples, Counts };
const char* levelText(Level level);

struct PassComparison {
  std::string name;
  size_t baselineCount = 0, newCount = 0;  // values tested: runs, or samples
  std::vector<double> baselineValues, newValues;  // those values (ms), drawn in compare.html
  double baselineMedian = 0, newMedian = 0;
  double logRatio = 0;        // ln(new median / baseline median): x2 and x0.5 are equally far
  double effectFloor = 0;     // smallest |logRatio| that matters: --min-effect and --min-effect-ms
  double threshold = 0;       // the floor or spread-multiple x the noisier side's spread, the larger: a
                              // change below it is `same` unless a run-level test confirms it
  double baselineSpread = 0;  // robust spread of the baseline's log values
  double newSpread = 0;       // same, of the new side: a disturbed run spreads, and its median moves
  double pValue = 1;          // Mann-Whitney U, two-sided
  bool exact = false;         // pValue from the exact distribution
  double pHolm = 1;           // Holm-adjusted over the judged names; significant when <= alpha
  double baselineLargerShare = 0.5;  // U / (n1 n2): the share of (baseline, new) pairs where the baseline is larger
  Verdict verdict = Verdict::Unknown;
  std::optional<size_t> moreNeeded;  // for `unknown`: about how many more values a side would tell
  bool judged = true;         // false for host copies unless CompareOptions::judgeHostCopies: shown, never failing
  double ratio() const;
};

struct Comparison {
  Level level = Level::Samples;
  std::string measure = "time";  // time, instructions or cycles
  std::string baselineSource, newSource;
  size_t baselineRuns = 1, newRuns = 1;
  size_t judgedNames = 0;
  size_t fewestPerSide = 0;            // the fewest values a side that can reach a verdict at alpha
  std::vector<PassComparison> passes;  // names present on both sides, baseline order
  std::vector<std::string> onlyInBaseline, onlyInNew;
  bool significantSlowdown() const;  // some judged name is slower
  bool unknownJudged() const;        // some judged name is unknown
  bool fails(const CompareOptions& options) const;  // the exit status 1
};

Comparison compareTimings(const SideTimings& baseline, const SideTimings& candidate, const CompareOptions& options);
// One run a side.
Comparison compareTimings(const TimingSamples& baseline, const TimingSamples& candidate, const CompareOptions& options);

std::string comparisonTable(const Comparison& c, const CompareOptions& options = {});
nlohmann::json comparisonJson(const Comparison& c, const CompareOptions& options);

}  // namespace aor
