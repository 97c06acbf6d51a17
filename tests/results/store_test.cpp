// The SQLite store through the same interface PostgreSQL uses: the schema's version and
// migrations, recording, idempotence, refusals, and reading a history back in a fixed order.
#include <gtest/gtest.h>

#include <filesystem>
#include <unistd.h>

#include <SQLiteCpp/SQLiteCpp.h>
#include <fmt/format.h>

#include "core/input_error.h"
#include "results/schema.h"
#include "results/trend_report.h"
#include "results/store.h"

namespace aor::results {
namespace {
namespace fs = std::filesystem;

struct TempStore {
  fs::path folder = fs::temp_directory_path() / ("aor-store-test-" + std::to_string(getpid()) + "-" +
                                                 ::testing::UnitTest::GetInstance()->current_test_info()->name());
  fs::path file = folder / "store.sqlite";
  TempStore() {
    fs::remove_all(folder);
    fs::create_directories(folder);
  }
  ~TempStore() { fs::remove_all(folder); }
};

ReportInput report(const std::string& sha, double gtaoMs, const std::string& device = "llvmpipe") {
  ReportInput r;
  r.source = sha + "/report.json";
  r.reportSha256 = sha;
  r.series = {"boxes-orbit", "c0ffee", "gtao", R"({"slices":3,"technique":"gtao"})", "[0,4]", "isolated", device,
              "Mesa 22.3.6", "0.1"};
  r.passes = {{"gtao", {gtaoMs, gtaoMs * 1.01, gtaoMs * 0.99}, false, std::nullopt},
              {"upload", {0.2, 0.21}, true, std::nullopt}};
  return r;
}

CommitInfo commit(const std::string& sha, double ordinal) { return {sha, "main", "ordinal", ordinal}; }

TEST(ResultsStore, NewStoreIsMigratedToTheCurrentVersionInWalMode) {
  TempStore t;
  auto db = openDatabase(t.file.string(), true);
  migrate(*db);
  EXPECT_EQ(db->schemaVersion(), currentSchemaVersion());
  SQLite::Database raw(t.file.string());
  EXPECT_EQ(raw.execAndGet("PRAGMA user_version").getInt(), currentSchemaVersion());
  EXPECT_EQ(raw.execAndGet("PRAGMA journal_mode").getString(), "wal");
  migrate(*db);  // nothing left to do: no error, same version
  EXPECT_EQ(db->schemaVersion(), currentSchemaVersion());
}

TEST(ResultsStore, VersionOneStoreIsMigratedKeepingItsRows) {
  TempStore t;
  {
    // A store as the first schema left it: its tables, version 1, one commit.
    auto db = openDatabase(t.file.string(), true);
    migrate(*db);
    SQLite::Database raw(t.file.string(), SQLite::OPEN_READWRITE);
    raw.exec("ALTER TABLE series DROP COLUMN measure; ALTER TABLE series DROP COLUMN cost_key");
    raw.exec("DROP INDEX runs_by_series; DROP INDEX commits_by_position; PRAGMA user_version = 1");
    raw.exec("INSERT INTO commits (sha, branch, position_kind, position) VALUES ('old', 'main', 'ordinal', 1)");
    raw.exec("INSERT INTO series (fingerprint, capture_name, capture_sha256, technique, settings, frames, timing_mode, "
             "device, driver, tool_version) VALUES ('f', 'c', 's', 'gtao', '{}', '[0,1]', 'isolated', 'd', 'r', 'v')");
  }
  auto db = openDatabase(t.file.string(), true);
  migrate(*db);
  EXPECT_EQ(db->schemaVersion(), currentSchemaVersion());
  EXPECT_EQ(countRows(*db).commits, 1);
  SQLite::Database raw(t.file.string());
  EXPECT_EQ(raw.execAndGet("SELECT COUNT(*) FROM sqlite_master WHERE name = 'runs_by_series'").getInt(), 1);
  // Version 3: series recorded before counted cost measure time.
  EXPECT_EQ(raw.execAndGet("SELECT measure || '/' || cost_key FROM series WHERE fingerprint = 'f'").getString(), "time/");
}

TEST(ResultsStore, MissingStoreIsCreatedOnlyWhenAsked) {
  TempStore t;
  EXPECT_THROW(openDatabase(t.file.string(), false), InputError);
  EXPECT_FALSE(fs::exists(t.file));
  openDatabase("sqlite:" + t.file.string(), true);
  EXPECT_TRUE(fs::exists(t.file));
}

TEST(ResultsStore, NewerStoreIsRefused) {
  TempStore t;
  {
    SQLite::Database raw(t.file.string(), SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE);
    raw.exec("PRAGMA user_version = 99");
  }
  auto db = openDatabase(t.file.string(), true);
  EXPECT_THROW(migrate(*db), InputError);
}

TEST(ResultsStore, RecordingTheSameReportTwiceStoresItOnce) {
  TempStore t;
  auto db = openDatabase(t.file.string(), true);
  migrate(*db);
  auto first = recordRuns(*db, {report("a", 1.0), report("b", 1.1)}, commit("c1", 1), {{"runner", "ci-1"}});
  EXPECT_EQ(first.stored, 2u);
  auto again = recordRuns(*db, {report("a", 1.0), report("c", 1.2)}, commit("c1", 1), {});
  EXPECT_EQ(again.stored, 1u);
  EXPECT_EQ(again.alreadyThere, 1u);
  auto counts = countRows(*db);
  EXPECT_EQ(counts.series, 1);
  EXPECT_EQ(counts.commits, 1);
  EXPECT_EQ(counts.runs, 3);
  EXPECT_EQ(counts.runPasses, 6);
  EXPECT_EQ(counts.samples, 3 * 5);
}

TEST(ResultsStore, ConflictingRecordsAreRefusedAndLeaveNothing) {
  TempStore t;
  auto db = openDatabase(t.file.string(), true);
  migrate(*db);
  recordRuns(*db, {report("a", 1.0)}, commit("c1", 1), {});
  // The same report for another commit; the same commit at another position; dates in an ordinal store.
  EXPECT_THROW(recordRuns(*db, {report("d", 1.0), report("a", 1.0)}, commit("c2", 2), {}), InputError);
  EXPECT_THROW(recordRuns(*db, {report("e", 1.0)}, commit("c1", 5), {}), InputError);
  EXPECT_THROW(recordRuns(*db, {report("f", 1.0)}, CommitInfo{"c3", "", "date", 1.7e9}, {}), InputError);
  auto counts = countRows(*db);
  EXPECT_EQ(counts.runs, 1);  // "d" was inserted before "a" was refused: rolled back with it
  EXPECT_EQ(counts.commits, 1);
}

TEST(ResultsStore, HistoryComesBackInCommitOrderWhateverTheRecordingOrder) {
  TempStore t;
  auto db = openDatabase(t.file.string(), true);
  migrate(*db);
  recordRuns(*db, {report("z", 3.0)}, commit("third", 30), {});
  recordRuns(*db, {report("y", 1.5), report("x", 1.0)}, commit("first", 10), {});
  recordRuns(*db, {report("w", 2.0)}, commit("second", 20), {});
  recordRuns(*db, {report("v", 9.0, "other device")}, commit("second", 20), {});
  auto all = loadHistory(*db, "", std::nullopt);
  ASSERT_EQ(all.size(), 2u);
  const auto& h = all[0];  // "boxes-orbit gtao on llvmpipe" before "... on other device"? by device name
  EXPECT_EQ(h.key.device, "llvmpipe");
  ASSERT_EQ(h.commits.size(), 3u);
  EXPECT_EQ(h.commits[0].sha, "first");
  EXPECT_EQ(h.commits[1].sha, "second");
  EXPECT_EQ(h.commits[2].sha, "third");
  ASSERT_EQ(h.commits[0].runs.size(), 2u);
  EXPECT_EQ(h.commits[0].runs[0].reportSha256, "x");  // by report hash within a commit
  EXPECT_DOUBLE_EQ(h.commits[0].runs[0].passes[0].valueMs, 1.0);  // the median of 1.0, 1.01, 0.99
  auto filtered = loadHistory(*db, "other device", std::nullopt);
  ASSERT_EQ(filtered.size(), 1u);
  EXPECT_EQ(filtered[0].commits.size(), 1u);
  auto since = loadHistory(*db, "llvmpipe", commitPosition(*db, "second", "--since"));
  ASSERT_EQ(since.size(), 1u);
  EXPECT_EQ(since[0].commits.size(), 2u);
  EXPECT_THROW(commitPosition(*db, "nowhere", "--since"), InputError);
}

TEST(ResultsStore, TrendIsTheSameWhateverOrderTheRunsWereRecordedIn) {
  // 24 commits of 2 runs, x1.25 from commit 12; two stores get them in opposite orders, a commit's
  // two runs in separate records.
  std::vector<std::pair<CommitInfo, ReportInput>> runs;
  for (int c = 0; c < 24; ++c)
    for (int r = 0; r < 2; ++r) {
      double noise = 1 + 0.004 * ((c * 7 + r * 3) % 5 - 2) + 1e-5 * (2 * c + r);
      runs.push_back({commit("sha" + std::to_string(100 + c), c), report(fmt::format("r{}-{}", c, r), (c >= 12 ? 1.25 : 1.0) * noise)});
    }
  std::vector<std::string> json;
  for (bool reversed : {false, true}) {
    TempStore t;
    t.file = t.folder / (reversed ? "reversed.sqlite" : "forward.sqlite");
    auto db = openDatabase(t.file.string(), true);
    migrate(*db);
    for (size_t i = 0; i < runs.size(); ++i) {
      const auto& [c, r] = runs[reversed ? runs.size() - 1 - i : i];
      recordRuns(*db, {r}, c, {});
    }
    std::vector<TrendResult> results;
    for (auto& h : loadHistory(*db, "", std::nullopt)) {
      auto trend = findChangePoints(h, TrendOptions{});
      results.push_back({std::move(h), std::move(trend)});
    }
    ASSERT_EQ(results.size(), 1u);
    ASSERT_EQ(results[0].trend.changes.size(), 1u);
    EXPECT_EQ(results[0].history.commits[results[0].trend.changes[0].firstCommit].sha, "sha112");
    json.push_back(trendJson(results, TrendOptions{}).dump());
  }
  EXPECT_EQ(json[0], json[1]);
}

TEST(ResultsStore, DoublesRoundTripExactly) {
  TempStore t;
  auto db = openDatabase(t.file.string(), true);
  migrate(*db);
  double awkward = 0.1 + 0.2;  // 0.30000000000000004
  recordRuns(*db, {report("a", awkward)}, commit("c1", 1), {});
  auto h = loadHistory(*db, "", std::nullopt);
  EXPECT_EQ(h[0].commits[0].runs[0].passes[0].valueMs, awkward);
}

}  // namespace
}  // namespace aor::results
