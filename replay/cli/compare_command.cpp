// `aoreplay compare BASELINE NEW`: per pass verdicts from two report.json or Google Benchmark JSON
// files; exit 1 only when something got significantly slower.
#include <memory>
#include <regex>

#include <fmt/format.h>

#include "cli/commands.h"
#include "capture/input_error.h"
#include "cli/handlers.h"
#include "report/compare.h"
#include "report/output_directory.h"

namespace aor::cli {
namespace {

struct CompareArgs {
  std::string baseline, candidate, json;
  std::vector<std::string> ignore;
  CompareOptions options;
};

// Drops names matching any --ignore pattern (e.g. host-link copies that are not the algorithm).
TimingSamples withoutIgnored(TimingSamples samples, const std::vector<std::string>& patterns) {
  for (const auto& pattern : patterns) {
    std::regex re;
    try {
      re = std::regex(pattern);
    } catch (const std::regex_error& e) {
      throw InputError("", std::nullopt, "--ignore", fmt::format("\"{}\" is not a regular expression: {}", pattern, e.what()));
    }
    std::erase_if(samples, [&](const auto& series) { return std::regex_search(series.name, re); });
  }
  return samples;
}

int compareCommand(const CompareArgs& args) {
  auto comparison = compareTimings(withoutIgnored(loadTimingSamples(args.baseline), args.ignore),
                                   withoutIgnored(loadTimingSamples(args.candidate), args.ignore), args.options);
  if (comparison.passes.empty())
    throw InputError(args.candidate, std::nullopt, "", fmt::format("no pass or benchmark name in common with {}", args.baseline));
  fmt::print("{}", comparisonTable(comparison));
  if (!args.json.empty()) writeFileAtomically(args.json, comparisonJson(comparison, args.options).dump(2) + "\n");
  return comparison.significantSlowdown() ? kExitFailed : kExitOk;
}

}  // namespace

void registerCompareCommand(CLI::App& app) {
  auto args = std::make_shared<CompareArgs>();
  auto* cmd = app.add_subcommand("compare", "compare GPU times of two runs (report.json or Google Benchmark JSON)");
  cmd->add_option("baseline", args->baseline, "baseline report.json or benchmark JSON")->required();
  cmd->add_option("new", args->candidate, "new report.json or benchmark JSON")->required();
  cmd->add_option("--json", args->json, "also write the verdicts as JSON to this file");
  cmd->add_option("--ignore", args->ignore, "skip names matching this regular expression (repeatable)");
  cmd->add_option("--alpha", args->options.alpha, "false-alarm rate over all names (Bonferroni split)")
      ->check(CLI::Range(1e-9, 0.5));
  cmd->add_option("--min-effect", args->options.minEffect, "smallest relative median change that counts")
      ->check(CLI::Range(0.0, 10.0));
  cmd->add_option("--min-effect-ms", args->options.minEffectMs,
                  "smallest absolute median change that counts, in milliseconds (default 0.001)")
      ->check(CLI::Range(0.0, 1e6));
  cmd->add_option("--spread-multiple", args->options.spreadMultiple,
                  "the change must also exceed this many spreads (robust, relative) of the noisier run")
      ->check(CLI::Range(0.0, 100.0));
  cmd->add_flag("--judge-host-copies", args->options.judgeHostCopies,
                "let the upload and read-back copies fail the comparison too (by default they are shown, not judged)");
  handlers()["compare"] = [args] { return compareCommand(*args); };
}

}  // namespace aor::cli
