#pragma once
// Change points in a series' history (aoreplay trend): one value per run (its median), tested at
// every commit boundary over a window of runs on each side with the exact Mann-Whitney U test
// (core/compare_stats.h), the Hodges-Lehmann shift and its interval (shift_estimate.h), Holm
// over the passes at the boundary, and Bonferroni over the boundaries scanned (a scan of B
// boundaries is B chances of a false alarm). Deterministic: the same runs give the same answer
// whatever order they were recorded in. A counted series (run --cost) is exact: each commit's
// value against the next commit's, a change of at least minEffectCounts is one, without tests
// (one run a side suffices). The rules and why: results/README.md.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "results/store.h"

namespace aor::results {

struct TrendOptions {
  size_t window = 30;       // runs a side at most
  size_t minRuns = 4;       // runs a side at least, else the boundary is not tested
  double alpha = 0.05;      // false-alarm rate per series and segment
  double minEffect = 0.02;  // smallest shift that counts, as a ratio either way (x1.02 or x1/1.02)
  // A counted series': the smallest change that counts (no statistics); unset: the measure's
  // default (report/compare.h countsMinEffect: x1.001 instructions, x1.01 cycles).
  std::optional<double> minEffectCounts;
  double confidence = 0.95; // of the shift's interval
};

struct PassShift {
  std::string pass;
  size_t before = 0, after = 0;  // runs tested on each side
  double beforeMedianMs = 0, afterMedianMs = 0;
  double ratio = 1, lower = 1, upper = 1;  // Hodges-Lehmann shift of log values as a ratio, and its interval
  double intervalConfidence = 0;
  double pValue = 1, pHolm = 1;  // exact U test; Holm-adjusted over the passes at this boundary
  double separation = 0;         // |U / (before x after) - 1/2|: 1/2 when the sides do not overlap
  bool changed = false;          // pHolm <= the scan's level and |ln ratio| >= ln(1 + minEffect)
};

struct ChangePoint {
  size_t firstCommit = 0;  // index into SeriesHistory::commits: the first commit after the change
  size_t lastCommit = 0;   // > firstCommit: a suspect range, the boundaries in it tie (need more runs)
  bool slower = false;     // the most significant changed pass got slower
  double level = 0;        // the level the boundary was tested at: alpha / boundaries scanned
  std::vector<PassShift> passes;  // every judged pass at the boundary, changed or not
  bool isRange() const { return lastCommit != firstCommit; }
};

struct SeriesTrend {
  std::vector<std::string> judged;         // passes in every run: compute passes and the total
  size_t runs = 0;
  std::vector<ChangePoint> changes;        // in commit order
  bool newSlowdown() const;                // the newest change is a slowdown
};

SeriesTrend findChangePoints(const SeriesHistory& history, const TrendOptions& options);

}  // namespace aor::results
