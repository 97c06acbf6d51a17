// `aoreplay trend --db URL [--series FILTER] [--since SHA]`: change points per series of the
// results store; exit 1 when a series' newest change is a slowdown (for CI).
#include <filesystem>
#include <memory>

#include <fmt/format.h>

#include "core/input_error.h"
#include "cli/commands.h"
#include "cli/handlers.h"
#include "cli/number_options.h"
#include "cli/results_options.h"
#include "core/output_directory.h"
#include "results/schema.h"
#include "results/trend_report.h"

namespace aor::cli {
namespace {

struct TrendArgs {
  std::string db = kDefaultStore;
  std::string series, since, junit, json, plot;
  results::TrendOptions options;
};

int trend(const TrendArgs& args) {
  auto db = results::openDatabase(args.db, false);
  results::migrate(*db);
  std::optional<double> since;
  if (!args.since.empty()) since = results::commitPosition(*db, args.since, "--since");
  std::vector<results::TrendResult> found;
  for (auto& history : results::loadHistory(*db, args.series, since)) {
    auto trend = results::findChangePoints(history, args.options);
    found.push_back({std::move(history), std::move(trend)});
  }
  if (found.empty())
    throw InputError(db->displayName(), std::nullopt, "--series",
                     args.series.empty() ? "the store holds no runs" : fmt::format("no series matches {}", args.series));
  bool toStdout = args.json == "-";
  fmt::print(toStdout ? stderr : stdout, "{}", results::trendTable(found, args.options));
  if (!args.json.empty()) writeFileAtomically(args.json, results::trendJson(found, args.options).dump(2) + "\n", {});
  if (!args.junit.empty()) writeFileAtomically(args.junit, results::trendJUnit(found), {});
  if (!args.plot.empty()) {
    std::filesystem::create_directories(args.plot);
    for (const auto& r : found)
      writeFileAtomically(std::filesystem::path(args.plot) / results::plotFileName(r), results::trendPlot(r), {});
  }
  bool slower = std::any_of(found.begin(), found.end(), [](const auto& r) { return r.trend.newSlowdown(); });
  return slower ? kExitFailed : kExitOk;
}

}  // namespace

void registerTrendCommand(CLI::App& app) {
  auto args = std::make_shared<TrendArgs>();
  auto* cmd = app.add_subcommand("trend", "change points of every series in a results store; exit 1 on a new slowdown");
  addStoreOption(*cmd, args->db);
  cmd->add_option("--series", args->series, "only series whose fingerprint starts with, or whose label contains, this");
  cmd->add_option("--since", args->since, "only runs of this recorded commit and later ones");
  cmd->add_option("--window", args->options.window, "runs a side tested at a boundary, at most (default 30)")
      ->check(wholeIn(4, 50));
  cmd->add_option("--min-runs", args->options.minRuns, "runs a side a boundary needs to be tested (default 4)")
      ->check(wholeIn(2, 50));
  cmd->add_option("--alpha", args->options.alpha, "false-alarm rate per series over the boundaries scanned (default 0.05)")
      ->check(numberIn(1e-9, 0.5));
  cmd->add_option("--min-effect", args->options.minEffect,
                  "smallest shift that counts, as a ratio either way (default 0.02; counted series: 0.001 instructions, 0.01 cycles)")
      ->check(numberIn(0.0, 10.0))
      ->each([options = &args->options](const std::string& value) { options->minEffectCounts = std::stod(value); });
  cmd->add_option("--junit", args->junit, "also write JUnit XML (a test case per series and pass; a new slowdown fails)");
  cmd->add_option("--json", args->json, "also write the change points as JSON (- for standard output)");
  cmd->add_option("--plot", args->plot, "write a plot per series into this folder (FINGERPRINT12.svg)");
  handlers()["trend"] = [args] {
    if (args->options.minRuns > args->options.window)
      throw InputError("", std::nullopt, "--min-runs", "cannot be more than --window");
    return trend(*args);
  };
}

}  // namespace aor::cli
