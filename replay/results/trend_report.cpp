#include "results/trend_report.h"

#include <algorithm>

#include <fmt/format.h>

#include "core/compare_stats.h"
#include "report/svg_plot.h"

namespace aor::results {
namespace {

std::string shortSha(const std::string& sha) { return sha.substr(0, 12); }

std::string where(const SeriesHistory& h, const ChangePoint& c) {
  const auto& first = h.commits[c.firstCommit];
  if (!c.isRange()) return fmt::format("first commit after the change: {}", first.sha);
  return fmt::format("suspect range {}..{}, need more runs", first.sha, h.commits[c.lastCommit].sha);
}

}  // namespace

// One change point: the passes at its boundary, as tested (timed) or as counted (exact).
std::string changeText(const SeriesHistory& h, const ChangePoint& c, const TrendOptions& o) {
  const bool counted = h.key.counted();
  std::string out = fmt::format("  {}: {}\n", c.slower ? "SLOWER" : "faster", where(h, c));
  if (counted) {
    out += fmt::format("    {:<22} {:>6} {:>16} {:>16} {:>10}\n", "pass", "runs", "before", "after", "change");
    for (const auto& p : c.passes)
      out += fmt::format("    {:<22} {:>6} {:>16.0f} {:>16.0f} {:>10}{}\n", p.pass, fmt::format("{}+{}", p.before, p.after),
                         p.beforeMedianMs, p.afterMedianMs, fmt::format("x{:.5f}", p.ratio), p.changed ? "  changed" : "");
    return out + fmt::format("    ({} counted under callgrind: changed at x{:.4g} or more either way)\n",
                             h.key.measure, 1 + o.minEffectCounts.value_or(countsMinEffect(h.key.measure)));
  }
  out += fmt::format("    {:<22} {:>6} {:>10} {:>10} {:>8} {:>19} {:>10} {:>10}\n", "pass", "runs", "before ms",
                     "after ms", "shift", "interval", "p", "p (Holm)");
  for (const auto& p : c.passes)
    out += fmt::format("    {:<22} {:>6} {:>10.4f} {:>10.4f} {:>8} {:>19} {:>10.2e} {:>10.2e}{}\n", p.pass,
                       fmt::format("{}+{}", p.before, p.after), p.beforeMedianMs, p.afterMedianMs,
                       fmt::format("x{:.3f}", p.ratio), fmt::format("[x{:.3f}, x{:.3f}]", p.lower, p.upper),
                       p.pValue, p.pHolm, p.changed ? "  changed" : "");
  return out + fmt::format("    (changed: p (Holm) <= {:.2e}, alpha {} over the boundaries scanned, and a shift of at least x{:.2f})\n",
                           c.level, o.alpha, 1 + o.minEffect);
}

std::string trendTable(const std::vector<TrendResult>& results, const TrendOptions& o) {
  std::string out;
  for (const auto& r : results) {
    const auto& h = r.history;
    out += fmt::format("series {} {}: {} commits, {} runs\n", shortSha(h.fingerprint), h.key.label(), h.commits.size(),
                       r.trend.runs);
    if (r.trend.changes.empty() && h.key.counted()) {
      out += fmt::format("  no change ({} counted under callgrind; minimum effect x{:.4g})\n", h.key.measure, 1 + o.minEffectCounts.value_or(countsMinEffect(h.key.measure)));
      continue;
    }
    if (r.trend.changes.empty()) {
      out += fmt::format("  no change (windows of {} runs a side, at least {}; minimum effect x{:.2f})\n", o.window,
                         o.minRuns, 1 + o.minEffect);
      continue;
    }
    for (const auto& c : r.trend.changes) out += changeText(h, c, o);
  }
  size_t slow = std::count_if(results.begin(), results.end(), [](const auto& r) { return r.trend.newSlowdown(); });
  out += fmt::format("{} series, {} with a new slowdown\n", results.size(), slow);
  return out;
}

nlohmann::json trendJson(const std::vector<TrendResult>& results, const TrendOptions& o) {
  nlohmann::json series = nlohmann::json::array();
  for (const auto& r : results) {
    const auto& h = r.history;
    nlohmann::json changes = nlohmann::json::array();
    for (const auto& c : r.trend.changes) {
      nlohmann::json passes = nlohmann::json::array();
      for (const auto& p : c.passes)
        passes.push_back({{"pass", p.pass}, {"runs_before", p.before}, {"runs_after", p.after},
                          {h.key.counted() ? "before_value" : "before_median_ms", p.beforeMedianMs},
                          {h.key.counted() ? "after_value" : "after_median_ms", p.afterMedianMs},
                          {"ratio", p.ratio}, {"interval", {p.lower, p.upper}},
                          {"interval_confidence", p.intervalConfidence}, {"p", p.pValue}, {"p_holm", p.pHolm},
                          {"changed", p.changed}});
      changes.push_back({{"first_commit", h.commits[c.firstCommit].sha},
                         {"last_commit", h.commits[c.lastCommit].sha},
                         {"range", c.isRange()},
                         {"direction", c.slower ? "slower" : "faster"},
                         {"level", c.level},
                         {"passes", passes}});
    }
    series.push_back({{"fingerprint", h.fingerprint}, {"label", h.key.label()}, {"measure", h.key.measure},
                      {"capture", h.key.captureName},
                      {"technique", h.key.technique}, {"device", h.key.device}, {"driver", h.key.driver},
                      {"commits", h.commits.size()}, {"runs", r.trend.runs}, {"judged", r.trend.judged},
                      {"changes", changes}, {"new_slowdown", r.trend.newSlowdown()}});
  }
  return {{"tool", "aoreplay"},
          {"options", {{"window", o.window}, {"min_runs", o.minRuns}, {"alpha", o.alpha}, {"min_effect", o.minEffect},
                       {"confidence", o.confidence}}},
          {"series", series}};
}

std::string trendJUnit(const std::vector<TrendResult>& results) {
  size_t tests = 0, failures = 0;
  std::string cases;
  for (const auto& r : results) {
    const ChangePoint* newest = r.trend.changes.empty() ? nullptr : &r.trend.changes.back();
    for (const auto& pass : r.trend.judged) {
      ++tests;
      std::string classname = escapeXml(fmt::format("{} {}", shortSha(r.history.fingerprint), r.history.key.label()));
      cases += fmt::format("    <testcase classname=\"{}\" name=\"{}\"", classname, escapeXml(pass));
      const PassShift* shift = nullptr;
      if (newest && newest->slower)
        for (const auto& p : newest->passes)
          if (p.pass == pass && p.changed && p.ratio > 1) shift = &p;
      if (!shift) {
        cases += "/>\n";
        continue;
      }
      ++failures;
      std::string message = fmt::format("slower x{:.3f} [x{:.3f}, x{:.3f}], {}", shift->ratio, shift->lower, shift->upper,
                                        where(r.history, *newest));
      cases += fmt::format(">\n      <failure message=\"{}\" type=\"slowdown\"/>\n    </testcase>\n", escapeXml(message));
    }
  }
  return fmt::format(
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites>\n  <testsuite name=\"aoreplay trend\" tests=\"{}\" "
      "failures=\"{}\" errors=\"0\">\n{}  </testsuite>\n</testsuites>\n",
      tests, failures, cases);
}

std::string plotFileName(const TrendResult& result) { return shortSha(result.history.fingerprint) + ".svg"; }

std::string trendPlot(const TrendResult& r) {
  const auto& h = r.history;
  std::vector<PlotSeries> series;
  for (const auto& pass : r.trend.judged) {
    PlotSeries medians{pass, {}, {}, true, true, {}, {}};
    PlotSeries runs{pass + " (each run)", {}, {}, false, true, {}, {}};
    for (size_t c = 0; c < h.commits.size(); ++c) {
      std::vector<double> values;
      for (const auto& run : h.commits[c].runs)
        for (const auto& p : run.passes)
          if (p.name == pass) values.push_back(p.valueMs);
      if (values.empty()) continue;
      medians.x.push_back(double(c));
      medians.y.push_back(medianOf(values));
      for (double v : values) runs.x.push_back(double(c)), runs.y.push_back(v);
    }
    series.push_back(std::move(medians));
    series.push_back(std::move(runs));
  }
  PlotOptions options;
  options.title = fmt::format("{} {} on {} ({}): medians per commit, change points dashed", h.key.captureName,
                              h.key.technique, h.key.device.substr(0, h.key.device.find(" (")), shortSha(h.fingerprint));
  options.xLabel = fmt::format("commit (in {} order; {} .. {})", h.positionKind,
                               h.commits.empty() ? "" : shortSha(h.commits.front().sha),
                               h.commits.empty() ? "" : shortSha(h.commits.back().sha));
  options.yLabel = h.key.counted() ? h.key.measure : "GPU ms";
  options.logY = true;
  options.width = 1000;
  for (const auto& c : r.trend.changes) {
    options.verticalMarkers.push_back(double(c.firstCommit) - 0.5);
    if (c.isRange()) options.verticalMarkers.push_back(double(c.lastCommit) - 0.5);  // a suspect range: both ends
  }
  return svgPlot(series, options);
}

}  // namespace aor::results
