#include "report/html/sweep_page.h"

#include <algorithm>

#include <fmt/format.h>

#include "report/html/html_page.h"

namespace aor::html {
namespace {


// Every key of every technique in the sweep, in the order first declared (as sweep.csv).
std::vector<std::string> keyNames(const std::vector<SweepRow>& rows) {
  std::vector<std::string> keys;
  for (const auto& row : rows)
    for (const auto& p : row.config.settings.technique().parameters)
      if (std::find(keys.begin(), keys.end(), p.key) == keys.end()) keys.push_back(p.key);
  return keys;
}

std::string numberCell(double value, const char* format) {
  return fmt::format("<td data-value=\"{:.9g}\">{}</td>", value, fmt::format(fmt::runtime(format), value));
}

std::string configurationsTable(const std::vector<SweepRow>& rows) {
  auto passes = sweepPassNames(rows);
  auto keys = keyNames(rows);
  Table table{"configurations", {"#", "configuration", "technique"}, {}, true};
  for (const auto& k : keys) table.header.push_back(k);
  for (const auto& p : passes) table.header.push_back(p + " ms");
  for (const char* h : {"total ms", "RMSE", "SSIM", "Pareto"}) table.header.push_back(h);
  for (size_t i = 0; i < rows.size(); ++i) {
    const SweepRow& row = rows[i];
    const Settings& s = row.config.settings;
    std::vector<std::string> cells{fmt::format("<td data-value=\"{}\">{}</td>", i + 1, i + 1), escape(row.config.name),
                                   escape(s.technique().name)};
    for (const auto& k : keys) cells.push_back(s.has(k) ? escape(s.text(k)) : "");
    for (const auto& p : passes) {
      auto it = std::find_if(row.passMs.begin(), row.passMs.end(), [&](const auto& e) { return e.first == p; });
      cells.push_back(it == row.passMs.end() ? "" : numberCell(it->second, "{:.4f}"));
    }
    cells.push_back(numberCell(row.totalMs, "{:.4f}"));
    cells.push_back(numberCell(row.rmse, "{:.5f}"));
    cells.push_back(numberCell(row.ssim, "{:.4f}"));
    cells.push_back(row.pareto ? "<td class=\"pass\">yes</td>" : "no");
    table.rows.push_back(std::move(cells));
  }
  return table.html();
}

}  // namespace

std::string sweepPageHtml(const SweepInfo& info, const std::vector<SweepRow>& rows) {
  Page page(fmt::format("aoreplay sweep: {} ({} configurations)", info.capture, rows.size()));
  page.section("overview", "Sweep",
               factList({{"capture", info.capture},
                         {"frames", fmt::format("{}:{} (half-open)", info.frameBegin, info.frameEnd)},
                         {"device", info.device},
                         {"error against", info.referenceKind + " reference"},
                         {"timing", fmt::format("warm-up {}, {} timed run(s) per frame", info.warmup, info.repeat)}}));
  page.section("pareto", "Error against GPU time",
               "<div class=\"plot\">" + sweepSvg(info, rows) +
                   "</div>\n<p class=\"note\">Numbers are the configurations of the table below; hover a point for its "
                   "name and values. Filled: Pareto-optimal (no other configuration is both at least as fast and at "
                   "least as accurate).</p>\n");
  page.section("configurations-section", "Configurations (click a heading to sort)", configurationsTable(rows));
  return page.html();
}

}  // namespace aor::html
