// Change points on histories built in memory: a step is named at its commit, a flat history raises
// nothing, the order runs were stored in does not matter, an ambiguous commit gives a range, and
// fewer than min-runs a side is never judged.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>

#include "results/change_points.h"

namespace aor::results {
namespace {

// Deterministic noise on every platform: mt19937's output is specified, std's distributions are not.
struct Noise {
  std::mt19937 engine;
  explicit Noise(unsigned seed) : engine(seed) {}
  double uniform() { return (double(engine()) + 0.5) / 4294967296.0; }
  // A log-normal-ish factor of relative spread `sigma` (sum of uniforms: close enough to normal).
  double factor(double sigma) {
    double sum = 0;
    for (int i = 0; i < 12; ++i) sum += uniform();
    return std::exp(sigma * (sum - 6));
  }
};

// `commits` commits of `runsPerCommit` runs each; from commit `stepAt` on, gtao is x`step`.
SeriesHistory history(size_t commits, size_t runsPerCommit, size_t stepAt, double step, double sigma, unsigned seed) {
  Noise noise(seed);
  SeriesHistory h;
  h.fingerprint = "0123456789abcdef";
  h.key.captureName = "boxes-orbit";
  h.key.technique = "gtao";
  h.key.device = "test device";
  h.positionKind = "ordinal";
  std::int64_t id = 0;
  for (size_t c = 0; c < commits; ++c) {
    StoredCommit commit{"commit" + std::to_string(100 + c), "main", double(c), {}};
    for (size_t r = 0; r < runsPerCommit; ++r) {
      double gtao = 2.0 * (c >= stepAt ? step : 1.0) * noise.factor(sigma);
      double blur = 0.5 * noise.factor(sigma);
      StoredRun run{++id, "report" + std::to_string(id), "", {}};
      run.passes = {{"gtao", false, gtao}, {"blur", false, blur}, {"upload", true, 0.3 * noise.factor(0.2)},
                    {"total", false, gtao + blur}};
      commit.runs.push_back(run);
    }
    h.commits.push_back(commit);
  }
  return h;
}

TEST(ChangePoints, StepIsNamedAtItsCommit) {
  for (unsigned seed = 1; seed <= 10; ++seed) {
    auto trend = findChangePoints(history(40, 1, 25, 1.20, 0.02, seed), TrendOptions{});
    ASSERT_EQ(trend.changes.size(), 1u) << "seed " << seed;
    const auto& c = trend.changes[0];
    EXPECT_EQ(c.firstCommit, 25u) << "seed " << seed;
    EXPECT_FALSE(c.isRange()) << "seed " << seed;
    EXPECT_TRUE(c.slower);
    EXPECT_TRUE(trend.newSlowdown());
    for (const auto& p : c.passes) {
      if (p.pass == "gtao") {
        EXPECT_TRUE(p.changed);
        EXPECT_NEAR(p.ratio, 1.20, 0.03);
        EXPECT_LT(p.lower, p.ratio);
        EXPECT_GT(p.upper, p.ratio);
      }
      if (p.pass == "blur") {
        EXPECT_FALSE(p.changed) << "seed " << seed;
      }
    }
  }
}

TEST(ChangePoints, HostCopiesAreNotJudged) {
  auto trend = findChangePoints(history(20, 1, 100, 1.0, 0.02, 3), TrendOptions{});
  EXPECT_EQ(trend.judged, (std::vector<std::string>{"blur", "gtao", "total"}));
}

TEST(ChangePoints, FlatHistoryRaisesNothing) {
  int alarms = 0;
  for (unsigned seed = 1; seed <= 40; ++seed)
    alarms += !findChangePoints(history(40, 1, 1000, 1.0, 0.03, seed), TrendOptions{}).changes.empty();
  EXPECT_LE(alarms, 2);
}

TEST(ChangePoints, SpeedUpIsNotANewSlowdown) {
  auto trend = findChangePoints(history(30, 2, 15, 0.8, 0.02, 5), TrendOptions{});
  ASSERT_EQ(trend.changes.size(), 1u);
  EXPECT_FALSE(trend.changes[0].slower);
  EXPECT_FALSE(trend.newSlowdown());
}

TEST(ChangePoints, SmallerThanTheMinimumEffectIsNoChange) {
  // x1.015 with almost no noise is significant but below the 2 % that counts.
  auto trend = findChangePoints(history(40, 1, 20, 1.015, 0.001, 7), TrendOptions{});
  EXPECT_TRUE(trend.changes.empty());
  TrendOptions finer;
  finer.minEffect = 0.01;
  EXPECT_EQ(findChangePoints(history(40, 1, 20, 1.015, 0.001, 7), finer).changes.size(), 1u);
}

TEST(ChangePoints, RecordingOrderDoesNotMatter) {
  auto h = history(30, 3, 12, 1.2, 0.03, 9);
  auto reference = findChangePoints(h, TrendOptions{});
  // loadHistory orders a commit's runs by report hash: here, reversing them in each commit and
  // sorting them back is what any recording order becomes.
  for (auto& c : h.commits) std::reverse(c.runs.begin(), c.runs.end());
  for (auto& c : h.commits)
    std::sort(c.runs.begin(), c.runs.end(), [](const auto& a, const auto& b) { return a.reportSha256 < b.reportSha256; });
  auto again = findChangePoints(h, TrendOptions{});
  ASSERT_EQ(again.changes.size(), reference.changes.size());
  EXPECT_EQ(again.changes[0].firstCommit, reference.changes[0].firstCommit);
  EXPECT_EQ(again.changes[0].passes[1].pValue, reference.changes[0].passes[1].pValue);
}

TEST(ChangePoints, AmbiguousCommitGivesASuspectRange) {
  auto h = history(30, 1, 15, 1.3, 0.01, 11);
  // Commit 15's one run lies half-way between the old and the new times: the change is at commit
  // 15 or 16, and one run cannot tell.
  for (auto& p : h.commits[15].runs[0].passes)
    if (p.name == "gtao" || p.name == "total") p.valueMs /= 1.14;
  auto trend = findChangePoints(h, TrendOptions{});
  ASSERT_EQ(trend.changes.size(), 1u);
  EXPECT_TRUE(trend.changes[0].isRange());
  EXPECT_EQ(trend.changes[0].firstCommit, 15u);
  EXPECT_EQ(trend.changes[0].lastCommit, 16u);
}

TEST(ChangePoints, DisturbedRunNextToTheChangeGivesASuspectRange) {
  auto h = history(30, 1, 15, 1.3, 0.01, 17);
  // Commit 14's one run took twice as long (another process on the machine): it is slower than
  // either side, so it cannot say whether the change came before it or after it.
  for (auto& p : h.commits[14].runs[0].passes) p.valueMs *= 2;
  auto trend = findChangePoints(h, TrendOptions{});
  ASSERT_EQ(trend.changes.size(), 1u);
  EXPECT_EQ(trend.changes[0].firstCommit, 14u);
  EXPECT_EQ(trend.changes[0].lastCommit, 15u);
}

TEST(ChangePoints, NewestRunsAreJudgedOnceEnoughFollowTheChange) {
  // 3 runs after the step: the boundary at it is not testable with at least 4 a side; the one a
  // commit earlier (one old run and the 3 new ones after it) may be significant, and then the old
  // run next to it makes it a suspect range up to the step, never a named commit.
  auto three = findChangePoints(history(30, 1, 27, 1.5, 0.01, 13), TrendOptions{});
  ASSERT_LE(three.changes.size(), 1u);
  if (!three.changes.empty()) {
    EXPECT_TRUE(three.changes[0].isRange());
    EXPECT_LE(three.changes[0].firstCommit, 27u);
    EXPECT_EQ(three.changes[0].lastCommit, 27u);
  }
  // 4 after, 27 before: 2/C(31, 4) x 3 passes = 1.9e-4, under 0.05 over the 24 boundaries scanned: named.
  auto four = findChangePoints(history(31, 1, 27, 1.5, 0.01, 13), TrendOptions{});
  ASSERT_EQ(four.changes.size(), 1u);
  EXPECT_EQ(four.changes[0].firstCommit, 27u);
  // With a window of 10 the 4 runs after face 10 before: 2/C(14, 4) x 3 = 6e-3, not enough.
  TrendOptions narrow;
  narrow.window = 10;
  EXPECT_TRUE(findChangePoints(history(31, 1, 27, 1.5, 0.01, 13), narrow).changes.empty());
}

}  // namespace
}  // namespace aor::results

namespace aor::results {
namespace {

// A counted series: exact values, one run a commit; from commit `stepAt` on gtao is x`step`.
SeriesHistory countedHistory(size_t commits, size_t stepAt, double step) {
  SeriesHistory h = history(commits, 1, commits, 1.0, 0.0, 1);  // flat and noise-free
  h.key.measure = "instructions";
  h.key.costKey = "instructions|test device|...";
  for (size_t c = stepAt; c < commits; ++c)
    for (auto& p : h.commits[c].runs[0].passes)
      if (p.name == "gtao" || p.name == "total") p.valueMs *= p.name == "gtao" ? step : (2.0 * step + 0.5) / 2.5;
  return h;
}

TEST(ChangePoints, CountedSeriesChangeAtTheFirstCommitThatDiffersWithOneRunASide) {
  auto trend = findChangePoints(countedHistory(6, 4, 1.002), TrendOptions{});
  ASSERT_EQ(trend.changes.size(), 1u);
  EXPECT_EQ(trend.changes[0].firstCommit, 4u);
  EXPECT_FALSE(trend.changes[0].isRange());
  EXPECT_TRUE(trend.newSlowdown());
  for (const auto& p : trend.changes[0].passes) {
    EXPECT_EQ(p.before, 1u);
    EXPECT_EQ(p.changed, p.pass == "gtao" || p.pass == "total") << p.pass;
  }
}

TEST(ChangePoints, CountedSeriesBelowTheMinimumEffectIsNoChange) {
  EXPECT_TRUE(findChangePoints(countedHistory(6, 4, 1.0005), TrendOptions{}).changes.empty());
  TrendOptions finer;
  finer.minEffectCounts = 0.0001;
  EXPECT_EQ(findChangePoints(countedHistory(6, 4, 1.0005), finer).changes.size(), 1u);
  // The same history read as time (statistics, at least 4 runs a side) finds nothing in one run a commit.
  SeriesHistory timed = countedHistory(6, 4, 1.5);
  timed.key.measure = "time";
  EXPECT_TRUE(findChangePoints(timed, TrendOptions{}).changes.empty());
}

TEST(SeriesKeys, CountsStartSeriesOfTheirOwnAndTimedFingerprintsStayAsTheyWere) {
  SeriesKey timed;
  timed.captureSha256 = "abc";
  timed.technique = "gtao";
  SeriesKey counted = timed, otherCpu = timed;
  counted.measure = otherCpu.measure = "instructions";
  counted.costKey = "instructions|lavapipe|Mesa|CPU A|valgrind-3.19.0|";
  otherCpu.costKey = "instructions|lavapipe|Mesa|CPU B|valgrind-3.19.0|";
  EXPECT_NE(timed.fingerprint(), counted.fingerprint());
  EXPECT_NE(counted.fingerprint(), otherCpu.fingerprint());
  SeriesKey timedWithKey = timed;
  timedWithKey.costKey = "ignored for time";
  EXPECT_EQ(timed.fingerprint(), timedWithKey.fingerprint());
}

}  // namespace
}  // namespace aor::results
