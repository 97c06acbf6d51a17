// `aoreplay compare BASELINE NEW`: per pass verdicts from two report.json or Google Benchmark JSON
// files; exit 1 only when something got significantly slower.
#include <memory>

#include <fmt/format.h>

#include "cli/commands.h"
#include "capture/input_error.h"
#include "cli/handlers.h"
#include "report/compare.h"
#include "report/run_outputs.h"

namespace aor::cli {
namespace {

struct CompareArgs {
  std::string baseline, candidate, json;
  CompareOptions options;
};

int compareCommand(const CompareArgs& args) {
  auto comparison = compareTimings(loadTimingSamples(args.baseline), loadTimingSamples(args.candidate), args.options);
  if (comparison.passes.empty())
    throw InputError(args.candidate, std::nullopt, "", fmt::format("no pass or benchmark name in common with {}", args.baseline));
  fmt::print("{}", comparisonTable(comparison));
  if (!args.json.empty()) writeJson(args.json, comparisonJson(comparison, args.options));
  return comparison.significantSlowdown() ? kExitFailed : kExitOk;
}

}  // namespace

void registerCompareCommand(CLI::App& app) {
  auto args = std::make_shared<CompareArgs>();
  auto* cmd = app.add_subcommand("compare", "compare GPU times of two runs (report.json or Google Benchmark JSON)");
  cmd->add_option("baseline", args->baseline, "baseline report.json or benchmark JSON")->required();
  cmd->add_option("new", args->candidate, "new report.json or benchmark JSON")->required();
  cmd->add_option("--json", args->json, "also write the verdicts as JSON to this file");
  cmd->add_option("--alpha", args->options.alpha, "false-alarm rate over all names (Bonferroni split)")
      ->check(CLI::Range(1e-9, 0.5));
  cmd->add_option("--min-effect", args->options.minEffect, "smallest relative median change that counts")
      ->check(CLI::Range(0.0, 10.0));
  cmd->add_option("--spread-multiple", args->options.spreadMultiple,
                  "the change must also exceed this many baseline spreads (robust, relative)")
      ->check(CLI::Range(0.0, 100.0));
  handlers()["compare"] = [args] { return compareCommand(*args); };
}

}  // namespace aor::cli
