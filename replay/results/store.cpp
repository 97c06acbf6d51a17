#include "results/store.h"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>

#include <fmt/chrono.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/input_error.h"

namespace aor::results {
namespace {

// AOREPLAY_TEST_KILL_AFTER=record-inserted: SIGKILL right after every row is written and before
// the commit, so tests can show a killed record leaves no partial run.
void testKillPoint(const char* step) {
  static const char* killAfter = std::getenv("AOREPLAY_TEST_KILL_AFTER");
  if (killAfter && std::strcmp(killAfter, step) == 0) std::raise(SIGKILL);
}

std::string utcNow() {
  return fmt::format("{:%Y-%m-%dT%H:%M:%SZ}", fmt::gmtime(std::chrono::system_clock::to_time_t(std::chrono::system_clock::now())));
}

std::int64_t commitId(Database& db, const CommitInfo& commit) {
  std::optional<std::int64_t> id;
  db.query("SELECT id, position_kind, position FROM commits WHERE sha = ?", {commit.sha}, [&](const Row& row) {
    if (row.text(1) != commit.positionKind || row.real(2) != commit.position)
      throw InputError("", std::nullopt, "--commit",
                       fmt::format("{} is in the store at {} {}; now given as {} {}", commit.sha, row.text(1),
                                   row.real(2), commit.positionKind, commit.position));
    id = row.integer(0);
  });
  if (id) return *id;
  db.query("SELECT position_kind FROM commits LIMIT 1", {}, [&](const Row& row) {
    if (row.text(0) != commit.positionKind)
      throw InputError("", std::nullopt, commit.positionKind == "ordinal" ? "--ordinal" : "--date",
                       fmt::format("this store orders commits by {}; give --{} instead", row.text(0),
                                   row.text(0) == "ordinal" ? "ordinal" : "date"));
  });
  std::vector<SqlValue> values{commit.sha, commit.branch.empty() ? SqlValue(nullptr) : SqlValue(commit.branch),
                               commit.positionKind, commit.position};
  return *db.integerOrNone(
      "INSERT INTO commits (sha, branch, position_kind, position) VALUES (?, ?, ?, ?) RETURNING id", values);
}

std::int64_t seriesId(Database& db, const SeriesKey& key) {
  std::string fingerprint = key.fingerprint();
  db.execute(
      "INSERT INTO series (fingerprint, capture_name, capture_sha256, technique, settings, frames, timing_mode, "
      "device, driver, tool_version, measure, cost_key) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?) "
      "ON CONFLICT (fingerprint) DO NOTHING",
      {fingerprint, key.captureName, key.captureSha256, key.technique, key.settings, key.frames, key.timingMode,
       key.device, key.driver, key.toolVersion, key.measure, key.costKey});
  return *db.integerOrNone("SELECT id FROM series WHERE fingerprint = ?", {fingerprint});
}

void insertRun(Database& db, const ReportInput& report, std::int64_t series, std::int64_t commit, const std::string& tags) {
  std::int64_t run = *db.integerOrNone(
      "INSERT INTO runs (report_sha256, series_id, commit_id, source, tags, recorded_at) VALUES (?, ?, ?, ?, ?, ?) "
      "RETURNING id",
      {report.reportSha256, series, commit, report.source, tags, utcNow()});
  for (const auto& pass : report.passes) {
    db.execute("INSERT INTO run_passes (run_id, pass, host_copy, value_ms, sample_count) VALUES (?, ?, ?, ?, ?)",
               {run, pass.name, std::int64_t(pass.hostCopy), pass.runValue(), std::int64_t(pass.samples.size())});
    for (size_t i = 0; i < pass.samples.size(); ++i)
      db.execute("INSERT INTO samples (run_id, pass, idx, ms) VALUES (?, ?, ?, ?)",
                 {run, pass.name, std::int64_t(i), pass.samples[i]});
  }
}

}  // namespace

RecordOutcome recordRuns(Database& db, const std::vector<ReportInput>& reports, const CommitInfo& commit,
                         const std::map<std::string, std::string>& tags) {
  std::string tagText = nlohmann::json(tags).dump();
  RecordOutcome outcome;
  WriteTransaction transaction(db, true);
  std::int64_t commitRow = commitId(db, commit);
  for (const auto& report : reports) {
    std::optional<std::string> recordedFor;
    db.query("SELECT c.sha FROM runs r JOIN commits c ON c.id = r.commit_id WHERE r.report_sha256 = ?",
             {report.reportSha256}, [&](const Row& row) { recordedFor = row.text(0); });
    if (recordedFor && *recordedFor != commit.sha)
      throw InputError(report.source, std::nullopt, "",
                       fmt::format("this report is already recorded for commit {}, not {}", *recordedFor, commit.sha));
    if (recordedFor) {
      ++outcome.alreadyThere;
      continue;
    }
    insertRun(db, report, seriesId(db, report.series), commitRow, tagText);
    ++outcome.stored;
  }
  testKillPoint("record-inserted");
  transaction.commit();
  return outcome;
}

std::vector<SeriesHistory> loadHistory(Database& db, const std::string& filter, std::optional<double> sincePosition) {
  std::vector<SeriesHistory> all;
  db.query(
      "SELECT id, fingerprint, capture_name, capture_sha256, technique, settings, frames, timing_mode, device, driver, "
      "tool_version, measure, cost_key FROM series",
      {}, [&](const Row& row) {
        SeriesHistory h;
        h.id = row.integer(0);
        h.fingerprint = row.text(1);
        h.key = {row.text(2), row.text(3), row.text(4), row.text(5), row.text(6), row.text(7), row.text(8), row.text(9),
                 row.text(10), row.text(11), row.text(12)};
        if (filter.empty() || h.fingerprint.starts_with(filter) || h.key.label().find(filter) != std::string::npos)
          all.push_back(std::move(h));
      });
  std::sort(all.begin(), all.end(), [](const auto& a, const auto& b) {
    return std::tie(a.key.captureName, a.key.technique, a.key.device, a.fingerprint) <
           std::tie(b.key.captureName, b.key.technique, b.key.device, b.fingerprint);
  });
  for (auto& h : all) {
    std::map<std::int64_t, StoredRun*> byId;
    db.query(
        "SELECT r.id, r.report_sha256, r.source, c.sha, c.branch, c.position, c.position_kind FROM runs r "
        "JOIN commits c ON c.id = r.commit_id WHERE r.series_id = ? AND c.position >= ? "
        "ORDER BY c.position, c.sha, r.report_sha256",
        {h.id, sincePosition.value_or(-1e300)}, [&](const Row& row) {
          if (h.commits.empty() || h.commits.back().sha != row.text(3))
            h.commits.push_back({row.text(3), row.isNull(4) ? "" : row.text(4), row.real(5), {}});
          h.positionKind = row.text(6);
          h.commits.back().runs.push_back({row.integer(0), row.text(1), row.text(2), {}});
        });
    for (auto& c : h.commits)
      for (auto& r : c.runs) byId[r.id] = &r;
    db.query(
        "SELECT p.run_id, p.pass, p.host_copy, p.value_ms FROM run_passes p JOIN runs r ON r.id = p.run_id "
        "WHERE r.series_id = ? ORDER BY p.run_id, p.pass",
        {h.id}, [&](const Row& row) {
          auto it = byId.find(row.integer(0));
          if (it != byId.end()) it->second->passes.push_back({row.text(1), row.integer(2) != 0, row.real(3)});
        });
  }
  return all;
}

double commitPosition(Database& db, const std::string& sha, const std::string& field) {
  std::optional<double> position;
  db.query("SELECT position FROM commits WHERE sha = ?", {sha}, [&](const Row& row) { position = row.real(0); });
  if (!position) throw InputError(db.displayName(), std::nullopt, field, fmt::format("no commit {} in the store", sha));
  return *position;
}

StoreCounts countRows(Database& db) {
  StoreCounts c;
  auto count = [&](const char* table) { return *db.integerOrNone(fmt::format("SELECT COUNT(*) FROM {}", table), {}); };
  c.series = count("series");
  c.commits = count("commits");
  c.runs = count("runs");
  c.runPasses = count("run_passes");
  c.samples = count("samples");
  return c;
}

}  // namespace aor::results
