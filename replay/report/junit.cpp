#include "report/junit.h"

#include <algorithm>

#include <fmt/format.h>

#include "report/html/html_page.h"

namespace aor {
namespace {

std::string thresholdName(const Threshold& t) { return fmt::format("{} {} {:.6g}", t.metric, t.isMax ? "<=" : ">=", t.limit); }

}  // namespace

std::string junitXml(const std::string& suite, const std::vector<JunitCase>& cases) {
  size_t failures = std::count_if(cases.begin(), cases.end(), [](const auto& c) { return c.failure.has_value(); });
  size_t skipped = std::count_if(cases.begin(), cases.end(), [](const auto& c) { return c.skipped; });
  using html::escape;  // the same five entities XML needs
  std::string xml = fmt::format("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"aoreplay\" tests=\"{0}\" failures=\"{1}\" errors=\"0\">\n"
                                "  <testsuite name=\"{2}\" tests=\"{0}\" failures=\"{1}\" errors=\"0\" skipped=\"{3}\">\n",
                                cases.size(), failures, escape(suite), skipped);
  for (const auto& c : cases) {
    xml += fmt::format("    <testcase classname=\"{}\" name=\"{}\">\n", escape(c.className), escape(c.name));
    if (c.failure) {
      std::string first = c.failure->substr(0, c.failure->find('\n'));
      xml += fmt::format("      <failure message=\"{}\" type=\"threshold\">{}</failure>\n", escape(first), escape(*c.failure));
    }
    if (c.skipped) xml += "      <skipped message=\"shown, not judged\"/>\n";
    if (!c.detail.empty()) xml += fmt::format("      <system-out>{}</system-out>\n", escape(c.detail));
    xml += "    </testcase>\n";
  }
  return xml + "  </testsuite>\n</testsuites>\n";
}

std::vector<JunitCase> expectationCases(const std::vector<Threshold>& thresholds, const std::vector<ExpectationFailure>& failures) {
  std::vector<JunitCase> cases;
  for (const auto& t : thresholds) {
    JunitCase c{"aoreplay.expect", thresholdName(t)};
    std::vector<std::string> broken;
    for (const auto& f : failures)
      if (f.threshold.metric == t.metric && f.threshold.isMax == t.isMax && f.threshold.limit == t.limit) broken.push_back(f.describe());
    if (!broken.empty()) c.failure = fmt::format("{}", fmt::join(broken, "\n"));
    cases.push_back(std::move(c));
  }
  return cases;
}

std::vector<JunitCase> comparisonCases(const Comparison& comparison, const CompareOptions& options) {
  std::vector<JunitCase> cases;
  for (const auto& p : comparison.passes) {
    JunitCase c{"aoreplay.compare", p.name};
    c.detail = fmt::format("{}: baseline median {:.6g} ms ({} {}), new {:.6g} ms ({}), x{:.4f}, p (Holm) {:.4g}", verdictText(p.verdict),
                           p.baselineMedian, p.baselineCount, levelText(comparison.level), p.newMedian, p.newCount, p.ratio(), p.pHolm);
    bool fails = p.judged && (p.verdict == Verdict::Slower || (options.failOnUnknown && p.verdict == Verdict::Unknown));
    if (fails)
      c.failure = fmt::format("{} is {}: {:.6g} ms -> {:.6g} ms (x{:.4f}, p (Holm) {:.4g})", p.name, verdictText(p.verdict),
                              p.baselineMedian, p.newMedian, p.ratio(), p.pHolm);
    c.skipped = !p.judged;
    cases.push_back(std::move(c));
  }
  return cases;
}

}  // namespace aor
