#pragma once
// `aoreplay compare`: per pass (or per benchmark), is the new run faster, slower or the same as the
// baseline? See compare_README.md for why the verdict does not cry wolf on a noisy runner.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace aor {

// Timing samples in milliseconds of one pass or benchmark.
struct TimingSeries {
  std::string name;
  std::vector<double> samples;
  bool hostCopy = false;  // the harness's upload or read-back (passes/pass_names.h): not judged by default
};
using TimingSamples = std::vector<TimingSeries>;  // in file order

// Reads report.json (passes[].gpu_ms.samples, plus "total": the per-run sum of the compute passes
// when every pass has the same runs) or Google Benchmark JSON (iteration entries' real_time, which
// is the manual GPU time when the benchmark uses it; a name whose first segment is a host-copy
// pass is a host copy). Throws InputError naming the file and field.
TimingSamples loadTimingSamples(const std::filesystem::path& path);

struct CompareOptions {
  double alpha = 0.01;          // family-wise false-alarm rate, split over the compared names
  double minEffect = 0.02;      // smallest relative median change worth a verdict
  double spreadMultiple = 2.0;  // ...and at least this many spreads (robust, relative) of the noisier run
  double minEffectMs = 0.001;   // ...and at least this absolute change: microsecond passes shift by
                                // a fraction of a microsecond between processes (compare_README.md)
  size_t minSamples = 5;        // per side; fewer cannot reach significance at useful alpha
  bool judgeHostCopies = false; // host copies vary with host memory placement from process to process
};

enum class Verdict { Same, Faster, Slower, Unknown };
const char* verdictText(Verdict v);

struct PassComparison {
  std::string name;
  size_t baselineCount = 0, newCount = 0;
  double baselineMedian = 0, newMedian = 0;
  double change = 0;          // (new - baseline) / baseline median
  double threshold = 0;       // minimum relative change that counts for this name (all three floors)
  double baselineSpread = 0;  // robust spread / median of the baseline
  double newSpread = 0;       // same, of the new run: a disturbed run spreads, and its median moves
  double pValue = 1;          // Mann-Whitney U, two-sided
  double alpha = 0;           // per-name level after the Bonferroni split
  Verdict verdict = Verdict::Unknown;
  bool judged = true;         // false for host copies unless CompareOptions::judgeHostCopies: shown, never failing
};

struct Comparison {
  std::vector<PassComparison> passes;  // names present in both, baseline order
  std::vector<std::string> onlyInBaseline, onlyInNew;
  bool significantSlowdown() const;  // some judged name is slower
};

Comparison compareTimings(const TimingSamples& baseline, const TimingSamples& candidate, const CompareOptions& options);
Verdict decideVerdict(const PassComparison& p, const CompareOptions& options);

std::string comparisonTable(const Comparison& c);
nlohmann::json comparisonJson(const Comparison& c, const CompareOptions& options);

}  // namespace aor
