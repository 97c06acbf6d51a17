#include "results/schema.h"

#include <string>
#include <vector>

#include <fmt/format.h>

#include "core/input_error.h"

namespace aor::results {
namespace {

// {id}: the dialect's auto-numbered key. Ids and positions are 64-bit (BIGINT), times double.
const std::vector<std::vector<std::string>> kMigrations = {
    // 1: series (what is timed, where), commits (where in history), runs (one report each, keyed by
    // its content so recording it twice stores it once), each pass's run value and samples.
    {
        "CREATE TABLE series (id {id}, fingerprint TEXT NOT NULL UNIQUE, capture_name TEXT NOT NULL, "
        "capture_sha256 TEXT NOT NULL, technique TEXT NOT NULL, settings TEXT NOT NULL, frames TEXT NOT NULL, "
        "timing_mode TEXT NOT NULL, device TEXT NOT NULL, driver TEXT NOT NULL, tool_version TEXT NOT NULL)",
        "CREATE TABLE commits (id {id}, sha TEXT NOT NULL UNIQUE, branch TEXT, position_kind TEXT NOT NULL, "
        "position DOUBLE PRECISION NOT NULL)",
        "CREATE TABLE runs (id {id}, report_sha256 TEXT NOT NULL UNIQUE, series_id BIGINT NOT NULL REFERENCES series(id), "
        "commit_id BIGINT NOT NULL REFERENCES commits(id), source TEXT NOT NULL, tags TEXT NOT NULL, "
        "recorded_at TEXT NOT NULL)",
        "CREATE TABLE run_passes (run_id BIGINT NOT NULL REFERENCES runs(id), pass TEXT NOT NULL, "
        "host_copy INTEGER NOT NULL, value_ms DOUBLE PRECISION NOT NULL, sample_count INTEGER NOT NULL, "
        "PRIMARY KEY (run_id, pass))",
        "CREATE TABLE samples (run_id BIGINT NOT NULL REFERENCES runs(id), pass TEXT NOT NULL, idx INTEGER NOT NULL, "
        "ms DOUBLE PRECISION NOT NULL, PRIMARY KEY (run_id, pass, idx))",
    },
    // 2: trend reads a series' runs in commit order.
    {
        "CREATE INDEX runs_by_series ON runs (series_id, commit_id)",
        "CREATE INDEX commits_by_position ON commits (position)",
    },
    // 3: counted cost: what a series' values measure, and what its counts depend on. Values of a
    // counted series (run_passes.value_ms, samples.ms) are counts.
    {
        "ALTER TABLE series ADD COLUMN measure TEXT NOT NULL DEFAULT 'time'",
        "ALTER TABLE series ADD COLUMN cost_key TEXT NOT NULL DEFAULT ''",
    },
};

std::string forDialect(std::string sql, Dialect dialect) {
  const std::string key = dialect == Dialect::Sqlite ? "INTEGER PRIMARY KEY" : "BIGSERIAL PRIMARY KEY";
  for (auto at = sql.find("{id}"); at != std::string::npos; at = sql.find("{id}")) sql.replace(at, 4, key);
  return sql;
}

}  // namespace

int currentSchemaVersion() { return int(kMigrations.size()); }

void migrate(Database& db) {
  WriteTransaction transaction(db, true);
  int version = db.schemaVersion();
  // An SQLite file without aoreplay's version that already holds tables is someone else's: the
  // store's tables were once added to it.
  if (version == 0 && db.dialect() == Dialect::Sqlite &&
      db.integerOrNone("SELECT count(*) FROM sqlite_master WHERE type = 'table'", {}).value_or(0) > 0)
    throw InputError(db.displayName(), std::nullopt, "--db",
                     "is an SQLite database of something else (it has tables and no aoreplay schema version): "
                     "give a new file or an aoreplay store");
  if (version > currentSchemaVersion())
    throw InputError(db.displayName(), std::nullopt, "schema version",
                     fmt::format("the store is at schema version {}; this aoreplay knows versions up to {}", version,
                                 currentSchemaVersion()));
  for (int step = version; step < currentSchemaVersion(); ++step)
    for (const auto& sql : kMigrations[size_t(step)]) db.execute(forDialect(sql, db.dialect()));
  if (version != currentSchemaVersion()) db.setSchemaVersion(currentSchemaVersion());
  transaction.commit();
}

}  // namespace aor::results
