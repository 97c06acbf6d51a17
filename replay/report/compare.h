#pragma once
// `aoreplay compare`: per pass (or per benchmark), is the new run faster, slower or the same as the
// baseline? See compare_README.md for why the verdict does not cry wolf on a noisy runner.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace aor {

// Timing samples in milliseconds per pass or benchmark name, in file order.
using TimingSamples = std::vector<std::pair<std::string, std::vector<double>>>;

// Reads report.json (passes[].gpu_ms.samples, plus "total": the per-run sum when every pass has
// the same runs) or Google Benchmark JSON (iteration entries' real_time, which is the manual GPU
// time when the benchmark uses it). Throws InputError naming the file and field.
TimingSamples loadTimingSamples(const std::filesystem::path& path);

struct CompareOptions {
  double alpha = 0.01;          // family-wise false-alarm rate, split over the compared names
  double minEffect = 0.02;      // smallest relative median change worth a verdict
  double spreadMultiple = 2.0;  // ...and at least this many baseline spreads (robust, relative)
  size_t minSamples = 5;        // per side; fewer cannot reach significance at useful alpha
};

enum class Verdict { Same, Faster, Slower, Unknown };
const char* verdictText(Verdict v);

struct PassComparison {
  std::string name;
  size_t baselineCount = 0, newCount = 0;
  double baselineMedian = 0, newMedian = 0;
  double change = 0;          // (new - baseline) / baseline median
  double threshold = 0;       // minimum relative change that counts for this name
  double baselineSpread = 0;  // robust spread / median of the baseline
  double pValue = 1;          // Mann-Whitney U, two-sided
  double alpha = 0;           // per-name level after the Bonferroni split
  Verdict verdict = Verdict::Unknown;
};

struct Comparison {
  std::vector<PassComparison> passes;  // names present in both, baseline order
  std::vector<std::string> onlyInBaseline, onlyInNew;
  bool significantSlowdown() const;
};

Comparison compareTimings(const TimingSamples& baseline, const TimingSamples& candidate, const CompareOptions& options);
Verdict decideVerdict(const PassComparison& p, const CompareOptions& options);

std::string comparisonTable(const Comparison& c);
nlohmann::json comparisonJson(const Comparison& c, const CompareOptions& options);

}  // namespace aor
