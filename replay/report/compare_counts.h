#pragma once
// `compare` on counted cost (report.json written by `run --cost instructions|cycles`, Google
// Benchmark JSON written by `ao_bench --cost=...`): counts of
// the same dependency key are exact, so one run a side suffices and a change of at least
// --min-effect (for counts 0.001) is `slower` or `faster` without statistics (compare_README.md,
// "Counts"). Used by compare.cpp only.
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "report/compare.h"

namespace aor {

// report.json's "cost" block, or time when it has none. InputError for an unknown measure.
RunMeasure measureOfReport(const nlohmann::json& report, const std::filesystem::path& path);

// Google Benchmark JSON of `ao_bench --cost=instructions|cycles`: its context's "aoreplay_cost"
// block (a JSON string), or time when it has none.
RunMeasure measureOfBenchmark(const nlohmann::json& doc, const std::filesystem::path& path);

// A counted report's values: per pass its per-frame counts (samples) and their total (the run's
// value), and "total": the compute passes' sums per frame and the report's MEASURE_total.
TimingSamples countedSamples(const nlohmann::json& report, const std::filesystem::path& path, const std::string& measure);

// The measure every run of both sides has, checked: InputError naming the runs when one side is
// timed and the other counted, the measures differ, or the counts depend on different things
// (the first differing dependency named).
std::string commonMeasure(const SideTimings& baseline, const SideTimings& candidate);

Comparison compareCounts(const SideTimings& baseline, const SideTimings& candidate, const std::string& measure,
                         const CompareOptions& options);

// The table's rows for counts (name, base, new, ratio, verdict).
std::string countsTable(const Comparison& c, size_t nameWidth);

}  // namespace aor
