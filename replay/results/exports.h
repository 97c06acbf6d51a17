#pragma once
// The store's runs in the formats other dashboards read (aoreplay export):
//   Google Benchmark JSON   one commit's runs, each run one repetition (real_time = the run's value
//                           in ms), so `compare.py benchmarks A.json B.json` compares two commits;
//   Bencher Metric Format   one commit: per series and pass a `latency` measure in nanoseconds
//                           (value: the median over the commit's runs; lower/upper: their min/max);
//   Otava (E-Divisive) CSV  every commit: a row per commit, time, commit, then the commit's median
//                           of each series' pass, one column per series and pass.
#include <string>
#include <vector>

#include "results/store.h"

namespace aor::results {

// The name every format uses for a series' pass: CAPTURE/TECHNIQUE/FINGERPRINT12/PASS.
std::string benchmarkName(const SeriesHistory& series, const std::string& pass);

std::string googleBenchmarkJson(const std::vector<SeriesHistory>& series, const std::string& commit);
std::string bencherMetricFormat(const std::vector<SeriesHistory>& series, const std::string& commit);
std::string otavaCsv(const std::vector<SeriesHistory>& series);

}  // namespace aor::results
