#pragma once
// What `aoreplay trend` prints and writes: the table, JSON, JUnit XML and a plot per series.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "results/change_points.h"

namespace aor::results {

struct TrendResult {
  SeriesHistory history;
  SeriesTrend trend;
};

std::string trendTable(const std::vector<TrendResult>& results, const TrendOptions& options);
nlohmann::json trendJson(const std::vector<TrendResult>& results, const TrendOptions& options);
// One test suite; one test case per series and judged pass, failing when the series' newest change
// is a slowdown of that pass.
std::string trendJUnit(const std::vector<TrendResult>& results);
// Commit on x (in order), each judged pass's median over the commit's runs on a log y axis, every
// run as a point (the spread), the change points as vertical lines.
std::string trendPlot(const TrendResult& result);
// The plot's file name: the first 12 characters of the fingerprint.
std::string plotFileName(const TrendResult& result);

}  // namespace aor::results
