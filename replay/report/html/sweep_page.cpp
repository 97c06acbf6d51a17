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

bool ofTechnique(const SweepRow& row, const std::string& technique) {
  return technique.empty() || row.config.settings.technique().name == technique;
}

// The configurations of `technique` (all when empty): its keys and passes as columns, so a
// sweep over several techniques shows each one's own columns only; with `totals` also the total,
// the errors and the Pareto flag.
std::string configurationsTable(const std::vector<SweepRow>& all, const std::string& technique, bool totals,
                                bool details = true) {
  std::vector<SweepRow> rows;
  std::vector<size_t> numbers;
  for (size_t i = 0; i < all.size(); ++i)
    if (ofTechnique(all[i], technique)) rows.push_back(all[i]), numbers.push_back(i + 1);
  auto passes = details ? sweepPassNames(rows) : std::vector<std::string>{};
  auto keys = details ? keyNames(rows) : std::vector<std::string>{};
  Table table{technique.empty() ? "configurations" : "configurations-" + technique, {"#", "configuration", "technique"}, {}, true};
  for (const auto& k : keys) table.header.push_back(k);
  const bool counted = !rows.empty() && rows.front().measure != "time";
  const std::string unit = counted ? rows.front().measure : "ms";
  const char* costFormat = counted ? "{:.0f}" : "{:.4f}";
  for (const auto& p : passes) table.header.push_back(p + " " + unit);
  if (totals) {
    table.header.push_back("total " + unit);
    for (const char* h : {"RMSE", "halo-band RMSE", "halo-band bias", "SSIM", "Pareto"}) table.header.push_back(h);
  }
  for (size_t i = 0; i < rows.size(); ++i) {
    const SweepRow& row = rows[i];
    const Settings& s = row.config.settings;
    std::vector<std::string> cells{fmt::format("<td data-value=\"{}\">{}</td>", numbers[i], numbers[i]),
                                   escape(row.config.name), escape(s.technique().name)};
    for (const auto& k : keys) cells.push_back(s.has(k) ? escape(s.text(k)) : "");
    for (const auto& p : passes) {
      auto it = std::find_if(row.passMs.begin(), row.passMs.end(), [&](const auto& e) { return e.first == p; });
      cells.push_back(it == row.passMs.end() ? "" : numberCell(it->second, costFormat));
    }
    if (totals) {
      cells.push_back(numberCell(row.totalMs, costFormat));
      cells.push_back(numberCell(row.rmse, "{:.5f}"));
      cells.push_back(numberCell(row.haloRmse, "{:.5f}"));
      cells.push_back(numberCell(row.haloBias, "{:+.4f}"));
      cells.push_back(numberCell(row.ssim, "{:.4f}"));
      cells.push_back(row.pareto ? "<td class=\"pass\">yes</td>" : "no");
    }
    table.rows.push_back(std::move(cells));
  }
  return table.html();
}

// One technique: one table. Several: the totals of every configuration, then each technique's
// passes apart.
std::string configurationsHtml(const std::vector<SweepRow>& rows) {
  const auto techniques = sweepTechniques(rows);
  if (techniques.size() <= 1) return configurationsTable(rows, "", true);
  std::string html = configurationsTable(rows, "", true, false);
  for (const auto& technique : techniques)
    html += "<h3>" + escape(technique) + ": passes and keys</h3>\n" + configurationsTable(rows, technique, false);
  return html;
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
  page.section("pareto", info.rank == SweepRank::HaloBand ? "Halo-band error against GPU time" : "Error against GPU time",
               "<div class=\"plot\">" + sweepSvg(info, rows) +
                   "</div>\n<p class=\"note\">Numbers are the configurations of the table below; hover a point for its "
                   "name and values. Filled: Pareto-optimal (no other configuration is both at least as fast and at "
                   "least as accurate).</p>\n");
  page.section("configurations-section", "Configurations (click a heading to sort)", configurationsHtml(rows));
  return page.html();
}

}  // namespace aor::html
