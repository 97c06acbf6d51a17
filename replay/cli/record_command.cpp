// `aoreplay record REPORT... --db URL --commit SHA (--ordinal N | --date DATE)`: stores every
// timed sample of every pass of each report in the results store, as runs of that commit.
#include <ctime>
#include <map>
#include <memory>

#include <fmt/format.h>

#include "core/input_error.h"
#include "cli/commands.h"
#include "cli/handlers.h"
#include "cli/number_options.h"
#include "cli/results_options.h"
#include "results/schema.h"
#include "results/store.h"

namespace aor::cli {
namespace {

struct RecordArgs {
  std::vector<std::string> reports;
  std::string db = kDefaultStore;
  std::string commit, branch, date;
  std::optional<std::int64_t> ordinal;
  std::vector<std::string> tags;
};

std::map<std::string, std::string> parseTags(const std::vector<std::string>& tags) {
  std::map<std::string, std::string> out;
  for (const auto& tag : tags) {
    auto eq = tag.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InputError("", std::nullopt, "--tag", fmt::format("{} is not KEY=VALUE", tag));
    if (!out.emplace(tag.substr(0, eq), tag.substr(eq + 1)).second)
      throw InputError("", std::nullopt, "--tag", fmt::format("{} given twice", tag.substr(0, eq)));
  }
  return out;
}

int record(const RecordArgs& args) {
  if (args.commit.find_first_not_of(" \t") == std::string::npos)
    throw InputError("", std::nullopt, "--commit", "is empty: runs are stored as runs of a commit");
  results::CommitInfo commit{args.commit, args.branch, args.ordinal ? "ordinal" : "date",
                             args.ordinal ? double(*args.ordinal) : parseCommitDate(args.date)};
  auto tags = parseTags(args.tags);
  // Every report is read and checked before the store is locked: the write lock is held only for the inserts.
  std::vector<results::ReportInput> reports;
  for (const auto& path : args.reports) reports.push_back(results::readReportInput(path));
  auto db = results::openDatabase(args.db, true);
  results::migrate(*db);
  auto outcome = results::recordRuns(*db, reports, commit, tags);
  fmt::print("recorded {} run{} for commit {} into {}", outcome.stored, outcome.stored == 1 ? "" : "s", commit.sha,
             db->displayName());
  if (outcome.alreadyThere) fmt::print(" ({} already there, not stored again)", outcome.alreadyThere);
  fmt::print("\n");
  return kExitOk;
}

}  // namespace

void registerRecordCommand(CLI::App& app) {
  auto args = std::make_shared<RecordArgs>();
  auto* cmd = app.add_subcommand("record", "store the timed samples of report.json files in a results store, as runs of a commit");
  cmd->add_option("reports", args->reports, "report.json files of aoreplay run")->required()->check(CLI::ExistingFile);
  addStoreOption(*cmd, args->db);
  cmd->add_option("--commit", args->commit, "the commit the runs timed (e.g. git rev-parse HEAD)")->required();
  cmd->add_option("--branch", args->branch, "its branch (kept with the commit)");
  auto* ordinal = cmd->add_option("--ordinal", args->ordinal,
                                  "the commit's position in history, a whole number (e.g. git rev-list --count HEAD)")
                     ->check(wholeIn(0, kLastPrintableSecond));
  auto* date = cmd->add_option("--date", args->date,
                               "or its commit date: YYYY-MM-DD[THH:MM[:SS]][Z|+HH:MM] or @SECONDS (git log -1 --format=@%ct)");
  ordinal->excludes(date);
  date->excludes(ordinal);
  cmd->add_option("--tag", args->tags, "KEY=VALUE kept with each run (repeatable), e.g. runner=ci-3");
  handlers()["record"] = [args] {
    if (!args->ordinal && args->date.empty())
      throw InputError("", std::nullopt, "--ordinal", "give the commit's position: --ordinal N or --date DATE");
    return record(*args);
  };
}

}  // namespace aor::cli
