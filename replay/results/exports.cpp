#include "results/exports.h"

#include <algorithm>
#include <chrono>
#include <map>
#include <set>

#include <fmt/chrono.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/compare_stats.h"

namespace aor::results {
namespace {

// pass -> the run values of that pass at `commit`, in run order.
std::map<std::string, std::vector<double>> valuesAt(const StoredCommit& commit) {
  std::map<std::string, std::vector<double>> values;
  for (const auto& run : commit.runs)
    for (const auto& p : run.passes) values[p.name].push_back(p.valueMs);
  return values;
}

const StoredCommit* findCommit(const SeriesHistory& h, const std::string& sha) {
  for (const auto& c : h.commits)
    if (c.sha == sha) return &c;
  return nullptr;
}

// Otava's time column: the commit date; an ordinal N as N seconds after 1970 (order is what counts).
std::string isoTime(double seconds) {
  auto t = std::chrono::system_clock::time_point(std::chrono::seconds(static_cast<long long>(seconds)));
  return fmt::format("{:%Y-%m-%dT%H:%M:%SZ}", fmt::gmtime(std::chrono::system_clock::to_time_t(t)));
}

std::string csvField(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace

std::string benchmarkName(const SeriesHistory& series, const std::string& pass) {
  return fmt::format("{}/{}/{}/{}", series.key.captureName, series.key.technique, series.fingerprint.substr(0, 12), pass);
}

std::string googleBenchmarkJson(const std::vector<SeriesHistory>& series, const std::string& commit) {
  nlohmann::json benchmarks = nlohmann::json::array();
  for (const auto& h : series) {
    const auto* c = findCommit(h, commit);
    if (!c) continue;
    for (const auto& [pass, values] : valuesAt(*c))
      for (size_t i = 0; i < values.size(); ++i) {
        std::string name = benchmarkName(h, pass);
        benchmarks.push_back({{"name", name}, {"family_index", 0}, {"per_family_instance_index", 0},
                              {"run_name", name}, {"run_type", "iteration"}, {"repetitions", values.size()},
                              {"repetition_index", i}, {"threads", 1}, {"iterations", 1},
                              {"real_time", values[i]}, {"cpu_time", values[i]}, {"time_unit", "ms"}});
        // A counted series' values are counts: a counter names them, the label says so.
        if (h.key.counted())
          benchmarks.back()[h.key.measure] = values[i],
          benchmarks.back()["label"] = h.key.measure + " counted under callgrind (real_time holds the count, not ms)";
      }
  }
  nlohmann::json context{{"executable", "aoreplay export"}, {"commit", commit}, {"num_cpus", 1},
                         {"mhz_per_cpu", 0},            {"cpu_scaling_enabled", false},
                         {"caches", nlohmann::json::array()}, {"library_build_type", "release"}};
  return nlohmann::json{{"context", context}, {"benchmarks", benchmarks}}.dump(2) + "\n";
}

std::string bencherMetricFormat(const std::vector<SeriesHistory>& series, const std::string& commit) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& h : series) {
    const auto* c = findCommit(h, commit);
    if (!c) continue;
    for (const auto& [pass, values] : valuesAt(*c)) {
      auto [lo, hi] = std::minmax_element(values.begin(), values.end());
      // Bencher's latency is in ns; a counted series' values go under a measure of their own name.
      const double scale = h.key.counted() ? 1.0 : 1e6;
      out[benchmarkName(h, pass)] = {{h.key.counted() ? h.key.measure : "latency",
                                      {{"value", medianOf(values) * scale}, {"lower_value", *lo * scale}, {"upper_value", *hi * scale}}}};
    }
  }
  return out.dump(2) + "\n";
}

std::string otavaCsv(const std::vector<SeriesHistory>& series) {
  // Columns: every (series, pass); rows: every commit of any series, by position then sha.
  std::vector<std::pair<const SeriesHistory*, std::string>> columns;
  for (const auto& h : series) {
    std::set<std::string> passes;
    for (const auto& c : h.commits)
      for (const auto& r : c.runs)
        for (const auto& p : r.passes) passes.insert(p.name);
    for (const auto& p : passes) columns.push_back({&h, p});
  }
  std::map<std::pair<double, std::string>, std::vector<std::string>> rows;
  for (size_t k = 0; k < columns.size(); ++k) {
    for (const auto& c : columns[k].first->commits) {
      auto& row = rows[{c.position, c.sha}];
      row.resize(columns.size());
      auto values = valuesAt(c);
      auto it = values.find(columns[k].second);
      if (it != values.end()) row[k] = fmt::format("{}", medianOf(it->second));
    }
  }
  std::string csv = "time,commit";
  for (const auto& [h, pass] : columns) csv += "," + csvField(benchmarkName(*h, pass));
  csv += "\n";
  for (auto& [key, row] : rows) {
    row.resize(columns.size());
    csv += isoTime(key.first) + "," + csvField(key.second);
    for (const auto& cell : row) csv += "," + cell;
    csv += "\n";
  }
  return csv;
}

}  // namespace aor::results
