#include "results/change_points.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <set>

#include "core/compare_stats.h"
#include "results/shift_estimate.h"

namespace aor::results {
namespace {

struct Flat {
  std::vector<size_t> commitOf;             // per run, in history order
  std::vector<std::vector<double>> logMs;   // per judged pass, per run
  std::vector<std::vector<double>> ms;
};

std::vector<std::string> judgedPasses(const SeriesHistory& h) {
  std::optional<std::set<std::string>> common;
  for (const auto& c : h.commits)
    for (const auto& r : c.runs) {
      std::set<std::string> names;
      for (const auto& p : r.passes)
        if (!p.hostCopy) names.insert(p.name);
      if (!common) common = names;
      else {
        std::set<std::string> both;
        std::set_intersection(common->begin(), common->end(), names.begin(), names.end(), std::inserter(both, both.end()));
        common = both;
      }
    }
  return common ? std::vector<std::string>(common->begin(), common->end()) : std::vector<std::string>{};
}

Flat flatten(const SeriesHistory& h, const std::vector<std::string>& judged) {
  Flat f;
  f.logMs.resize(judged.size());
  f.ms.resize(judged.size());
  for (size_t c = 0; c < h.commits.size(); ++c)
    for (const auto& r : h.commits[c].runs) {
      f.commitOf.push_back(c);
      for (size_t k = 0; k < judged.size(); ++k) {
        auto it = std::find_if(r.passes.begin(), r.passes.end(), [&](const auto& p) { return p.name == judged[k]; });
        f.ms[k].push_back(it->valueMs);
        f.logMs[k].push_back(std::log(it->valueMs));
      }
    }
  return f;
}

struct Boundary {
  size_t at = 0;  // first run after the boundary
  std::vector<PassShift> passes;
  // The deciding pass: of the changed ones, the most separated (|U / (m n) - 1/2|), then the one
  // with the largest contrast (the least-squares change-point statistic: the difference of the
  // sides' mean log values over its standard error). The separation, not the p-value, picks the
  // boundary: p also falls with the window's size, so a boundary one run off, with a run more on
  // its short side, could beat the true one on p while its sides overlap. The contrast breaks
  // ties of complete separation: ranks cannot see that a run at +2 % belongs with the 0 % side,
  // not with the +20 % one; means can.
  bool anyChanged = false;
  double separation = 0;
  double contrast = 0;
  size_t decidingPass = 0;
  bool slower = false;
};

std::vector<double> slice(const std::vector<double>& v, size_t from, size_t to) {
  return std::vector<double>(v.begin() + std::ptrdiff_t(from), v.begin() + std::ptrdiff_t(to));
}

// |mean(after) - mean(before)| / its standard error (pooled variance); infinite without spread.
double meanContrast(const std::vector<double>& before, const std::vector<double>& after) {
  auto mean = [](const std::vector<double>& v) {
    double sum = 0;
    for (double x : v) sum += x;
    return sum / double(v.size());
  };
  double mb = mean(before), ma = mean(after), squares = 0;
  for (double x : before) squares += (x - mb) * (x - mb);
  for (double x : after) squares += (x - ma) * (x - ma);
  double variance = squares / double(before.size() + after.size() - 2);
  double error = std::sqrt(variance * (1.0 / double(before.size()) + 1.0 / double(after.size())));
  return error > 0 ? std::abs(ma - mb) / error : std::numeric_limits<double>::infinity();
}

Boundary testBoundary(const Flat& f, const std::vector<std::string>& judged, size_t lo, size_t at, size_t hi,
                      const TrendOptions& o, double level) {
  Boundary b;
  b.at = at;
  size_t from = std::max(lo, at >= o.window ? at - o.window : 0), to = std::min(hi, at + o.window);
  std::vector<double> pValues, contrasts;
  for (size_t k = 0; k < judged.size(); ++k) {
    auto before = slice(f.logMs[k], from, at), after = slice(f.logMs[k], at, to);
    PassShift s;
    s.pass = judged[k];
    s.before = before.size();
    s.after = after.size();
    s.beforeMedianMs = medianOf(slice(f.ms[k], from, at));
    s.afterMedianMs = medianOf(slice(f.ms[k], at, to));
    auto test = mannWhitneyExact(before, after);
    s.pValue = test.pValue;
    s.separation = std::abs(test.u / double(before.size() * after.size()) - 0.5);
    double contrast = meanContrast(before, after);
    auto shift = hodgesLehmann(before, after, o.confidence);
    s.ratio = std::exp(shift.shift);
    s.lower = std::exp(shift.lower);
    s.upper = std::exp(shift.upper);
    s.intervalConfidence = shift.confidence;
    pValues.push_back(s.pValue);
    contrasts.push_back(contrast);
    b.passes.push_back(s);
  }
  auto holm = holmAdjusted(pValues);
  for (size_t k = 0; k < judged.size(); ++k) {
    auto& s = b.passes[k];
    s.pHolm = holm[k];
    double magnitude = std::abs(std::log(s.ratio));
    s.changed = s.pHolm <= level && magnitude >= std::log1p(o.minEffect);
    if (s.changed && (!b.anyChanged || s.separation > b.separation ||
                      (s.separation == b.separation && contrasts[k] > b.contrast))) {
      b.anyChanged = true;
      b.separation = s.separation;
      b.contrast = contrasts[k];
      b.decidingPass = k;
      b.slower = s.ratio > 1;
    }
  }
  return b;
}

// A boundary with a changed pass before one without; then the more separated; then the larger
// contrast.
bool better(const Boundary& a, const Boundary& b) {
  if (a.anyChanged != b.anyChanged) return a.anyChanged;
  return a.separation > b.separation || (a.separation == b.separation && a.contrast > b.contrast);
}

// The boundaries the change may lie at: the best one, widened over each neighbouring commit whose
// runs (their median) do not lie clearly on their own side, on the pass that decided the boundary.
// Placed on the line from the before median (0) to the after median (1), a commit before the
// boundary is clear within 1/3 of 0, one after it within 1/3 of 1. Between, it could be either;
// beyond the far side (a run slowed by something else, three times the change, say), it tells
// nothing about where the change is. With such a commit the runs cannot tell on which side of it
// the change happened. Never beyond a window of the boundary `at`. The pass and the two medians
// are the best (significant) boundary's.
std::pair<size_t, size_t> suspects(const Flat& f, const Boundary& best, size_t at, size_t lo, size_t hi,
                                   const TrendOptions& o) {
  size_t k = best.decidingPass;
  double before = std::log(best.passes[k].beforeMedianMs), after = std::log(best.passes[k].afterMedianMs);
  auto place = [&](size_t from, size_t to) { return (medianOf(slice(f.logMs[k], from, to)) - before) / (after - before); };
  size_t first = at, last = at;
  while (first > lo && at - first < o.window) {
    size_t start = first - 1;
    while (start > lo && f.commitOf[start - 1] == f.commitOf[first - 1]) --start;
    if (start == lo || std::abs(place(start, first)) <= 1.0 / 3) break;
    first = start;  // the change may be at the commit before the boundary
  }
  while (last < hi && last - at < o.window) {
    size_t end = last + 1;
    while (end < hi && f.commitOf[end] == f.commitOf[last]) ++end;
    if (end == hi || std::abs(place(last, end) - 1) <= 1.0 / 3) break;
    last = end;  // the change may be after the commit after the boundary
  }
  return {first, last};
}

// Where the change is, among the boundaries within a window of the best one whose deciding pass
// moved the same way (significant or not: the best boundary is the evidence that there is a
// change, this only places it): the boundary with the fewest commits on the wrong side of it, each commit taken
// as the median of its runs on the best boundary's deciding pass and placed between that
// boundary's before (0) and after (1) medians: a commit before the boundary within 1/3 of 1, or
// one after it within 1/3 of 0, is misplaced; one beyond either side (a disturbed run) counts for
// nothing. Ties keep the order of `better` (the separation first). The separation alone is
// enough on quiet runs; on a machine where other processes slow one run in seven down, a wide
// window holds several such runs, and ranks cannot tell a disturbed old run from a new one: the
// commits' medians can.
const Boundary* fewestMisplaced(const Flat& f, const std::vector<Boundary>& tested, const Boundary& best, size_t lo,
                                size_t hi, const TrendOptions& o) {
  size_t k = best.decidingPass;
  double before = std::log(best.passes[k].beforeMedianMs), after = std::log(best.passes[k].afterMedianMs);
  std::vector<std::pair<size_t, size_t>> commits;  // run ranges of the segment's commits
  for (size_t at = lo; at < hi;) {
    size_t end = at + 1;
    while (end < hi && f.commitOf[end] == f.commitOf[at]) ++end;
    commits.push_back({at, end});
    at = end;
  }
  std::vector<double> places;
  for (const auto& [from, to] : commits)
    places.push_back((medianOf(slice(f.logMs[k], from, to)) - before) / (after - before));
  auto misplaced = [&](size_t boundary) {
    size_t count = 0;
    for (size_t c = 0; c < commits.size(); ++c) {
      auto [from, to] = commits[c];
      if (to + o.window <= boundary || from >= boundary + o.window) continue;
      bool beforeSide = to <= boundary;
      if (beforeSide ? std::abs(places[c] - 1) <= 1.0 / 3 : std::abs(places[c]) <= 1.0 / 3) ++count;
    }
    return count;
  };
  const Boundary* chosen = &best;
  size_t fewest = misplaced(best.at);
  for (const auto& b : tested) {
    bool near = (b.at > best.at ? b.at - best.at : best.at - b.at) < o.window;
    bool sameWay = (b.passes[k].ratio > 1) == (best.passes[k].ratio > 1);
    if (!sameWay || !near) continue;
    size_t count = misplaced(b.at);
    if (count < fewest || (count == fewest && better(b, *chosen))) chosen = &b, fewest = count;
  }
  return chosen;
}

// Runs [lo, hi) hold no change found so far; finds the strongest boundary in them, then looks on
// each side of it.
void scan(const Flat& f, const std::vector<std::string>& judged, size_t lo, size_t hi, const TrendOptions& o,
          std::vector<ChangePoint>& out) {
  std::vector<size_t> testable;
  for (size_t at = lo + 1; at < hi; ++at) {
    if (f.commitOf[at] == f.commitOf[at - 1]) continue;
    size_t before = std::min(o.window, at - lo), after = std::min(o.window, hi - at);
    if (before >= o.minRuns && after >= o.minRuns) testable.push_back(at);
  }
  if (testable.empty()) return;
  double level = o.alpha / double(testable.size());
  std::vector<Boundary> tested;
  for (size_t at : testable) tested.push_back(testBoundary(f, judged, lo, at, hi, o, level));
  auto best = std::min_element(tested.begin(), tested.end(), better);  // earliest of equals: the first
  if (!best->anyChanged) return;
  const Boundary& chosen = *fewestMisplaced(f, tested, *best, lo, hi, o);
  auto [first, last] = suspects(f, *best, chosen.at, lo, hi, o);
  ChangePoint change;
  change.firstCommit = f.commitOf[first];
  change.lastCommit = f.commitOf[last];
  change.slower = best->slower;
  change.level = level;
  change.passes = best->passes;  // the evidence: the significant boundary's tests
  scan(f, judged, lo, first, o, out);
  out.push_back(change);
  scan(f, judged, last, hi, o, out);
}

// A counted series: a commit's value of a pass is the median of its runs (which agree).
std::vector<double> commitValues(const StoredCommit& commit, const std::vector<std::string>& judged) {
  std::vector<double> values;
  for (const auto& name : judged) {
    std::vector<double> runs;
    for (const auto& r : commit.runs)
      for (const auto& p : r.passes)
        if (p.name == name) runs.push_back(p.valueMs);
    values.push_back(medianOf(runs));
  }
  return values;
}

PassShift exactShift(const std::string& pass, size_t before, size_t after, double from, double to, double minEffect) {
  PassShift s;
  s.pass = pass;
  s.before = before;
  s.after = after;
  s.beforeMedianMs = from;
  s.afterMedianMs = to;
  s.ratio = s.lower = s.upper = to / from;
  s.intervalConfidence = 1;
  s.changed = std::abs(std::log(s.ratio)) >= std::log1p(minEffect);
  s.pValue = s.pHolm = s.changed ? 0 : 1;
  s.separation = s.changed ? 0.5 : 0;
  return s;
}

// Counts are exact: every boundary between two commits with runs is a change where a judged pass
// moved by at least minEffectCounts; the largest such move decides slower or faster.
void exactChanges(const SeriesHistory& h, const std::vector<std::string>& judged, const TrendOptions& o,
                  std::vector<ChangePoint>& out) {
  std::optional<size_t> previous;
  for (size_t c = 0; c < h.commits.size(); ++c) {
    if (h.commits[c].runs.empty()) continue;
    if (previous) {
      auto from = commitValues(h.commits[*previous], judged), to = commitValues(h.commits[c], judged);
      ChangePoint change{c, c, false, 0, {}};
      double largest = 0;
      for (size_t k = 0; k < judged.size(); ++k) {
        change.passes.push_back(exactShift(judged[k], h.commits[*previous].runs.size(), h.commits[c].runs.size(), from[k],
                                           to[k], o.minEffectCounts.value_or(countsMinEffect(h.key.measure))));
        double move = std::abs(std::log(change.passes.back().ratio));
        if (change.passes.back().changed && move > largest) largest = move, change.slower = to[k] > from[k];
      }
      if (largest > 0) out.push_back(std::move(change));
    }
    previous = c;
  }
}

}  // namespace

bool SeriesTrend::newSlowdown() const { return !changes.empty() && changes.back().slower; }

SeriesTrend findChangePoints(const SeriesHistory& history, const TrendOptions& options) {
  SeriesTrend trend;
  trend.judged = judgedPasses(history);
  for (const auto& c : history.commits) trend.runs += c.runs.size();
  if (trend.judged.empty() || trend.runs == 0) return trend;
  if (history.key.counted()) {
    exactChanges(history, trend.judged, options, trend.changes);
    return trend;
  }
  Flat flat = flatten(history, trend.judged);
  scan(flat, trend.judged, 0, flat.commitOf.size(), options, trend.changes);
  return trend;
}

}  // namespace aor::results
