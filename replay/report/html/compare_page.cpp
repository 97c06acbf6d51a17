#include "report/html/compare_page.h"

#include <cmath>

#include <fmt/format.h>

#include "report/html/charts.h"
#include "report/html/html_page.h"

namespace aor::html {
namespace {

std::string verdictCell(const PassComparison& p) {
  const char* css = p.verdict == Verdict::Slower && p.judged ? "fail" : p.verdict == Verdict::Faster ? "pass" : "";
  return fmt::format("<td class=\"verdict {}\">{}{}</td>", css, verdictText(p.verdict), p.judged ? "" : " (not judged)");
}

std::string verdictTable(const Comparison& c) {
  Table table{"verdicts", {"name", "verdict", "baseline median ms", "new median ms", "ratio", "threshold (ratio)", "p", "p (Holm)", "values a side"}, {}, true};
  for (const auto& p : c.passes)
    table.rows.push_back({escape(p.name), verdictCell(p), fmt::format("{:.5g}", p.baselineMedian), fmt::format("{:.5g}", p.newMedian),
                          fmt::format("x{:.4f}", p.ratio()), fmt::format("x{:.4f} either way", std::exp(p.threshold)),
                          fmt::format("{:.4g}", p.pValue), fmt::format("{:.4g}", p.pHolm),
                          fmt::format("{} / {}", p.baselineCount, p.newCount)});
  return table.html();
}

std::string distributions(const Comparison& c) {
  std::string html;
  for (const auto& p : c.passes) {
    StripPlot plot{p.name, p.baselineValues, p.newValues, p.baselineMedian * std::exp(-p.threshold),
                   p.baselineMedian * std::exp(p.threshold), verdictText(p.verdict)};
    html += fmt::format("<div class=\"distribution\" data-name=\"{}\"><h3>{}: {}{}</h3>\n{}</div>\n", escape(p.name), escape(p.name),
                        verdictText(p.verdict), p.judged ? "" : " (shown, not judged)", stripPlotSvg(plot));
  }
  return html;
}

}  // namespace

std::string comparePageHtml(const Comparison& c, const CompareOptions& options) {
  Page page(fmt::format("aoreplay compare: {}", c.fails(options) ? "FAILED (a judged name is slower)" : "no judged slowdown"));
  std::string level = c.level == Level::Runs
                          ? fmt::format("runs: one value per run ({} baseline, {} new)", c.baselineRuns, c.newRuns)
                          : std::string("samples: one run a side, its frames x repetitions (cannot see run-to-run variation)");
  page.section("overview", "Comparison",
               factList({{"baseline", c.baselineSource},
                         {"new", c.newSource},
                         {"values tested", level},
                         {"rule", fmt::format("Mann-Whitney U, Holm-corrected over {} judged name(s) at alpha {:g}; minimum effect x{:g} "
                                              "and {:g} ms", c.judgedNames, options.alpha, 1 + options.minEffect, options.minEffectMs)},
                         {"only in baseline", c.onlyInBaseline.empty() ? "(none)" : fmt::format("{}", fmt::join(c.onlyInBaseline, ", "))},
                         {"only in new", c.onlyInNew.empty() ? "(none)" : fmt::format("{}", fmt::join(c.onlyInNew, ", "))}}));
  page.section("verdicts-section", "Verdicts", verdictTable(c));
  page.section("distributions", "Both sides' values per name (shaded: the threshold band around the baseline median)", distributions(c));
  return page.html();
}

}  // namespace aor::html
