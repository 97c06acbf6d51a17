// `aoreplay export --db URL --format google-benchmark|bencher|otava [--commit SHA] --out FILE`:
// the store's runs for other dashboards (results/exports.h says what each holds).
#include <algorithm>
#include <memory>

#include <fmt/format.h>

#include "core/input_error.h"
#include "cli/commands.h"
#include "cli/handlers.h"
#include "cli/results_options.h"
#include "core/output_directory.h"
#include "results/exports.h"
#include "results/schema.h"

namespace aor::cli {
namespace {

struct ExportArgs {
  std::string db = kDefaultStore;
  std::string format, series, commit, out = "-";
};

// The newest commit any selected series has.
std::string newestCommit(const std::vector<results::SeriesHistory>& series) {
  const results::StoredCommit* newest = nullptr;
  for (const auto& h : series)
    for (const auto& c : h.commits)
      if (!newest || std::tie(c.position, c.sha) > std::tie(newest->position, newest->sha)) newest = &c;
  return newest ? newest->sha : "";
}

int exportRuns(const ExportArgs& args) {
  auto db = results::openDatabase(args.db, false);
  results::migrate(*db);
  auto series = results::loadHistory(*db, args.series, std::nullopt);
  if (series.empty()) throw InputError(db->displayName(), std::nullopt, "--series", "no series with runs matches");
  std::string commit = args.commit.empty() ? newestCommit(series) : args.commit;
  if (!args.commit.empty()) results::commitPosition(*db, commit, "--commit");  // must be recorded
  std::string text = args.format == "google-benchmark" ? results::googleBenchmarkJson(series, commit)
                     : args.format == "bencher"        ? results::bencherMetricFormat(series, commit)
                                                       : results::otavaCsv(series);
  writeFileAtomically(args.out, text, {});
  if (args.out != "-") fmt::print("wrote {} ({}{})\n", args.out, args.format, args.format == "otava" ? "" : ", commit " + commit);
  return kExitOk;
}

}  // namespace

void registerExportCommand(CLI::App& app) {
  auto args = std::make_shared<ExportArgs>();
  auto* cmd = app.add_subcommand("export", "write a results store's runs as Google Benchmark JSON, Bencher Metric Format or Otava CSV");
  addStoreOption(*cmd, args->db);
  cmd->add_option("--format", args->format, "google-benchmark, bencher or otava")
      ->required()
      ->check(CLI::IsMember({"google-benchmark", "bencher", "otava"}));
  cmd->add_option("--series", args->series, "only series whose fingerprint starts with, or whose label contains, this");
  cmd->add_option("--commit", args->commit, "the commit whose runs Google Benchmark and Bencher get (default: the newest)");
  cmd->add_option("--out", args->out, "the file (default - : standard output)");
  handlers()["export"] = [args] { return exportRuns(*args); };
}

}  // namespace aor::cli
