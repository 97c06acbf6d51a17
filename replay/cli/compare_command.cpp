// `aoreplay compare BASELINE NEW`: per pass verdicts from two sides, each a report.json, a Google
// Benchmark JSON file or a folder of report.json files (one per run); exit 1 only when something
// got significantly slower (or, with --fail-on-unknown, could not be judged).
#include "cli/compare_command.h"

#include <memory>

#include <fmt/format.h>
#include <re2/re2.h>

#include "core/input_error.h"
#include "core/json_input.h"
#include "cli/commands.h"
#include "cli/handlers.h"
#include "cli/number_options.h"
#include "report/compare_counts.h"
#include "report/html/compare_page.h"
#include "report/junit.h"
#include "core/output_directory.h"

namespace aor::cli {
namespace {

// Drops names matching any --ignore pattern (e.g. host-link copies that are not the algorithm).
// RE2 matches in time linear in the name and without recursion (std::regex recursed once per
// character and overflowed the stack on a 50 000-character name).
SideTimings withoutIgnored(SideTimings side, const std::vector<std::string>& patterns) {
  for (const auto& pattern : patterns) {
    RE2::Options options;
    options.set_log_errors(false);
    const RE2 re(pattern, options);
    if (!re.ok())
      throw InputError("", std::nullopt, "--ignore",
                       fmt::format("{} is not a regular expression (RE2 syntax): {}", quoteForMessage(pattern), re.error()));
    for (auto& run : side.runs)
      std::erase_if(run.series, [&](const auto& series) { return RE2::PartialMatch(series.name, re); });
  }
  return side;
}

struct CompareArgs {
  std::string baseline, candidate;
  CompareFlags flags;
};

}  // namespace

void addCompareFlags(CLI::App& cmd, CompareFlags& flags) {
  cmd.add_option("--json", flags.json, "also write the verdicts as JSON to this file (- for standard output)");
  cmd.add_option("--junit", flags.junit, "also write the verdicts as JUnit XML to this file (one test case per name)");
  cmd.add_option("--ignore", flags.ignore, "skip names matching this regular expression (repeatable)");
  auto timeOnly = [&flags](const char* name) {
    return [&flags, name](const std::string&) { flags.timeOnlyGiven.push_back(name); };
  };
  cmd.add_option("--alpha", flags.options.alpha, "false-alarm rate over all judged names (Holm)")
      ->check(numberIn(1e-9, 0.5))
      ->each(timeOnly("--alpha"))
      ->capture_default_str();
  cmd.add_option("--min-effect", flags.options.minEffect,
                 "smallest median change that counts, as a ratio either way (counted cost: default 0.001 for instructions, 0.01 for cycles)")
      ->check(numberIn(0.0, 10.0))
      ->each([&flags](const std::string& value) { flags.options.minEffectCounts = std::stod(value); })
      ->capture_default_str();
  cmd.add_option("--min-effect-ms", flags.options.minEffectMs,
                 "smallest absolute median change that counts, in milliseconds")
      ->check(numberIn(0.0, 1e6))
      ->each(timeOnly("--min-effect-ms"))
      ->capture_default_str();
  cmd.add_option("--spread-multiple", flags.options.spreadMultiple,
                 "spreads (robust, of log values) of the noisier side a change must exceed: to count at all with "
                 "within-run samples, to be unknown rather than same with runs")
      ->check(numberIn(0.0, 100.0))
      ->each(timeOnly("--spread-multiple"))
      ->capture_default_str();
  cmd.add_flag("--judge-host-copies", flags.options.judgeHostCopies,
               "let the upload and read-back copies fail the comparison too (by default they are shown, not judged)");
  cmd.add_flag("--fail-on-unknown", flags.options.failOnUnknown,
               "exit 1 also when a judged name is unknown (not enough runs to tell)");
}

Comparison judgeSides(SideTimings baseline, SideTimings candidate, const CompareFlags& flags) {
  std::string baselineSource = baseline.source, newSource = candidate.source;
  if (const std::string measure = commonMeasure(baseline, candidate); measure != "time" && !flags.timeOnlyGiven.empty())
    throw InputError("", std::nullopt, flags.timeOnlyGiven.front(),
                     fmt::format("{} is for timed runs; these runs count {}, which are exact and judged without "
                                 "statistics (only --min-effect applies)",
                                 flags.timeOnlyGiven.front(), measure));
  auto comparison = compareTimings(withoutIgnored(std::move(baseline), flags.ignore),
                                   withoutIgnored(std::move(candidate), flags.ignore), flags.options);
  if (comparison.passes.empty())
    throw InputError(newSource, std::nullopt, "", fmt::format("no pass or benchmark name in common with {}", baselineSource));
  return comparison;
}

int reportComparison(const Comparison& comparison, const CompareFlags& flags, const std::vector<std::filesystem::path>& inputs) {
  // With --json - the verdicts go to standard output, so the table goes to standard error.
  fmt::print(flags.json == "-" ? stderr : stdout, "{}", comparisonTable(comparison, flags.options));
  if (!flags.json.empty()) writeFileAtomically(flags.json, comparisonJson(comparison, flags.options).dump(2) + "\n", inputs);
  if (!flags.junit.empty())
    writeFileAtomically(flags.junit, junitXml("aoreplay compare", comparisonCases(comparison, flags.options)), inputs);
  if (!flags.html.empty()) writeFileAtomically(flags.html, html::comparePageHtml(comparison, flags.options), inputs);
  return comparison.fails(flags.options) ? kExitFailed : kExitOk;
}

void registerCompareCommand(CLI::App& app) {
  auto args = std::make_shared<CompareArgs>();
  auto* cmd = app.add_subcommand(
      "compare", "compare GPU times of two sides: report.json, Google Benchmark JSON, or a folder of report.json (one per run)");
  cmd->add_option("baseline", args->baseline, "baseline: report.json, benchmark JSON, or a folder of runs")->required();
  cmd->add_option("new", args->candidate, "new: report.json, benchmark JSON, or a folder of runs")->required();
  addCompareFlags(*cmd, args->flags);
  cmd->add_option("--html", args->flags.html, "also write compare.html (verdicts, both distributions, thresholds) to this file");
  handlers()["compare"] = [args] {
    return reportComparison(judgeSides(loadSide(args->baseline), loadSide(args->candidate), args->flags), args->flags,
                            {args->baseline, args->candidate});
  };
}

}  // namespace aor::cli
