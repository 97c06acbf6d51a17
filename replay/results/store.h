#pragma once
// The results store: recording runs (aoreplay record) and reading a series' history back
// (aoreplay trend, exports). The same SQL for SQLite and PostgreSQL (database.h).
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "results/database.h"
#include "results/report_input.h"

namespace aor::results {

// Where a commit lies in history, as given on the command line: an ordinal (--ordinal N, e.g. git
// rev-list --count) or a commit date (--date, ISO 8601 UTC). One store uses one kind.
struct CommitInfo {
  std::string sha;
  std::string branch;       // may be empty
  std::string positionKind; // "ordinal" or "date"
  double position = 0;      // the ordinal, or seconds since 1970 of the date
};

struct RecordOutcome {
  size_t stored = 0;       // runs added
  size_t alreadyThere = 0; // the same report was recorded before (for this commit): not stored again
};

// Records every report as one run of `commit`, in one transaction holding the store's write lock:
// after a kill the store holds all of them or none. A report recorded before for another commit,
// or a commit recorded before at another position, is bad input (InputError).
RecordOutcome recordRuns(Database& db, const std::vector<ReportInput>& reports, const CommitInfo& commit,
                         const std::map<std::string, std::string>& tags);

struct StoredPass {
  std::string name;
  bool hostCopy = false;
  double valueMs = 0;  // the run's one value: the median of its samples (the total's: gpu_ms_total_median);
                       // a counted series': the count over the run's frames
};
struct StoredRun {
  std::int64_t id = 0;
  std::string reportSha256;
  std::string source;
  std::vector<StoredPass> passes;
};
struct StoredCommit {
  std::string sha, branch;
  double position = 0;
  std::vector<StoredRun> runs;  // by report hash: the order never depends on who recorded first
};
struct SeriesHistory {
  std::int64_t id = 0;
  std::string fingerprint;
  SeriesKey key;
  std::string positionKind;
  std::vector<StoredCommit> commits;  // by position, then sha
};

// Every series whose fingerprint starts with `filter` or whose label contains it (all when
// empty), by label then fingerprint; only commits at or after `sincePosition` when given.
std::vector<SeriesHistory> loadHistory(Database& db, const std::string& filter, std::optional<double> sincePosition);
// The position of a recorded commit; InputError naming `field` when the store does not have it.
double commitPosition(Database& db, const std::string& sha, const std::string& field);

// Row counts, for tests and `aoreplay record`'s summary.
struct StoreCounts {
  std::int64_t series = 0, commits = 0, runs = 0, runPasses = 0, samples = 0;
};
StoreCounts countRows(Database& db);

}  // namespace aor::results
