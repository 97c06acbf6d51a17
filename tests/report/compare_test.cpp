// `aoreplay compare`: the Mann-Whitney U test (exact and approximate) against hand-computed values
// and brute-force enumeration, Holm's correction, the verdict rules, the false-alarm rate on
// same-distribution samples and on runs with run-to-run shifts, the input formats (report.json,
// Google Benchmark JSON, folders of runs) and the exit codes.
#include <algorithm>
#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/input_error.h"
#include "gpu_test_support.h"
#include "report/compare.h"
#include "core/compare_stats.h"

namespace aor {
namespace {

// U counted pair by pair (the definition), independent of the rank-sum implementation.
double pairCountU(const std::vector<double>& a, const std::vector<double>& b) {
  double u = 0;
  for (double x : a)
    for (double y : b) u += x > y ? 1.0 : x == y ? 0.5 : 0.0;
  return u;
}

double enumeratedP(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> all(a);
  all.insert(all.end(), b.begin(), b.end());
  size_t n = all.size();
  double observed = std::abs(pairCountU(a, b) - double(a.size() * b.size()) / 2);
  size_t extreme = 0, splits = 0;
  for (uint32_t mask = 0; mask < (1u << n); ++mask) {
    if (size_t(std::popcount(mask)) != a.size()) continue;
    std::vector<double> x, y;
    for (size_t i = 0; i < n; ++i) (mask & (1u << i) ? x : y).push_back(all[i]);
    ++splits;
    extreme += std::abs(pairCountU(x, y) - double(a.size() * b.size()) / 2) >= observed - 1e-9;
  }
  return double(extreme) / double(splits);
}

TEST(MannWhitney, SeparatedSamplesMatchTheNormalApproximationByHand) {
  std::vector<double> a{1, 2, 3, 4, 5}, b{6, 7, 8, 9, 10};
  auto r = mannWhitneyNormal(a, b);
  EXPECT_EQ(r.u, 0.0);
  // mean 12.5, variance 25 * 11 / 12; z = (12.5 - 0.5) / sqrt(22.9167) = 2.50672
  EXPECT_NEAR(r.z, 2.506718, 1e-5);
  EXPECT_NEAR(r.pValue, 0.0121858, 1e-6);
  auto swapped = mannWhitneyNormal(b, a);
  EXPECT_EQ(swapped.u, 25.0);
  EXPECT_NEAR(swapped.z, -r.z, 1e-12);
  EXPECT_NEAR(swapped.pValue, r.pValue, 1e-12);
}

TEST(MannWhitney, TiesUseMidranksAndTheTieCorrectedVariance) {
  std::vector<double> a{1, 2, 2, 3, 3, 3}, b{2, 3, 3, 4, 4, 5};
  auto r = mannWhitneyNormal(a, b);
  EXPECT_EQ(r.u, pairCountU(a, b));
  EXPECT_EQ(r.u, 7.0);
  // tie groups of 1,3,5,2,1 values: sum t^3-t = 150; variance 36/12 * (13 - 150/132) = 35.5909
  EXPECT_NEAR(r.z, 1.760029, 1e-5);
  EXPECT_NEAR(r.pValue, 0.0784029, 1e-6);
}

TEST(MannWhitney, AllValuesTiedGiveNoEvidence) {
  auto r = mannWhitneyNormal({2, 2, 2}, {2, 2});
  EXPECT_EQ(r.pValue, 1.0);
  EXPECT_EQ(r.z, 0.0);
  auto exact = mannWhitneyU({2, 2, 2}, {2, 2});
  EXPECT_TRUE(exact.exact);
  EXPECT_EQ(exact.pValue, 1.0);
}

TEST(MannWhitney, SmallSamplesGetTheExactDistribution) {
  // 5 a side, completely separated: 2 of the C(10, 5) = 252 splits are as extreme.
  auto r = mannWhitneyU({1, 2, 3, 4, 5}, {6, 7, 8, 9, 10});
  EXPECT_TRUE(r.exact);
  EXPECT_NEAR(r.pValue, 2.0 / 252, 1e-15);
  EXPECT_NEAR(smallestTwoSidedP(5, 5), 2.0 / 252, 1e-15);
  // {1, 2} against {3, 4}: U = 0 or 4 in 2 of 6 splits.
  EXPECT_NEAR(mannWhitneyU({1, 2}, {3, 4}).pValue, 1.0 / 3, 1e-15);
  // Ties: 1, 2, 2, 3 have midranks 1, 2.5, 2.5, 4, mean rank sum 5. {1, 2} sums 3.5; of the 6 splits,
  // {1, 2}, {1, 2'}, {2, 3}, {2', 3} are 1.5 or more from 5 ({1, 3} and {2, 2'} sum 5): p = 4/6.
  EXPECT_NEAR(mannWhitneyU({1, 2}, {2, 3}).pValue, 4.0 / 6, 1e-15);
  // Beyond the limit the approximation is used.
  std::vector<double> many(60), others(60);
  for (size_t i = 0; i < many.size(); ++i) many[i] = double(i), others[i] = double(i) + 0.5;
  EXPECT_FALSE(mannWhitneyU(many, others).exact);
}

// The exact p-value, by brute force: every way to split the pooled values into groups of a's and
// b's sizes, U counted pair by pair; p is the share of splits whose U is at least as far from
// n1 n2 / 2 as the observed one.
double enumeratedP(const std::vector<double>& a, const std::vector<double>& b);

TEST(MannWhitney, ExactPValueMatchesEnumerationWithTies) {
  std::mt19937 rng(31);
  std::uniform_int_distribution<int> value(0, 4);  // tiny range: ties everywhere
  for (int trial = 0; trial < 40; ++trial) {
    std::vector<double> a(2 + size_t(trial % 5)), b(3 + size_t(trial % 4));
    for (auto& v : a) v = value(rng);
    for (auto& v : b) v = value(rng) + (trial % 3 == 0 ? 2 : 0);  // some trials with a shift
    auto r = mannWhitneyU(a, b);
    ASSERT_TRUE(r.exact);
    EXPECT_NEAR(r.pValue, enumeratedP(a, b), 1e-12) << "trial " << trial;
    EXPECT_NEAR(mannWhitneyU(b, a).pValue, r.pValue, 1e-12) << "symmetric in the sides";
  }
}

TEST(MannWhitney, TheApproximationIsConservativeAtTheLimit) {
  // 50 a side (the largest exact size), with and without timestamp-like ties, shifts giving exact
  // p between 1e-4 and 0.05: the approximation's p is never below the exact one (it cannot add a
  // false alarm) and at most 40 % above it (measured: 1-35 %).
  std::mt19937 rng(8);
  std::normal_distribution<double> noise(0.0, 1.0);
  int checked = 0;
  for (int trial = 0; trial < 60; ++trial) {
    double shift = 0.4 + 0.05 * (trial % 10), quantum = trial % 2 ? 0.05 : 0.0;
    std::vector<double> a(50), b(50);
    auto draw = [&](double offset) {
      double v = noise(rng) + offset;
      return quantum > 0 ? std::round(v / quantum) * quantum : v;
    };
    for (auto& v : a) v = draw(0);
    for (auto& v : b) v = draw(shift);
    double exact = mannWhitneyExact(a, b).pValue, approximate = mannWhitneyNormal(a, b).pValue;
    if (exact < 1e-4 || exact > 0.05) continue;
    ++checked;
    EXPECT_GE(approximate, exact) << "trial " << trial;
    EXPECT_LE(approximate, 1.4 * exact) << "trial " << trial << ": exact " << exact << ", normal " << approximate;
  }
  EXPECT_GE(checked, 20);
}

TEST(MannWhitney, FewestPerSideAndHolm) {
  EXPECT_EQ(fewestPerSide(0.05), 4u);       // 2/70 = 0.029; 3 a side: 2/20 = 0.1
  EXPECT_EQ(fewestPerSide(0.05 / 6), 5u);   // 2/252 = 0.0079 <= 0.0083
  EXPECT_EQ(fewestPerSide(0.05 / 8), 6u);   // 0.0079 > 0.00625; 2/924 = 0.0022
  // Sorted 0.005 (x4 = 0.02), 0.01 (x3 = 0.03), 0.03 (x2 = 0.06), 0.04 (x1, but never below 0.06).
  auto adjusted = holmAdjusted({0.01, 0.04, 0.03, 0.005});
  std::vector<double> expected{0.03, 0.06, 0.06, 0.02};
  for (size_t i = 0; i < expected.size(); ++i) EXPECT_NEAR(adjusted[i], expected[i], 1e-15) << i;
  EXPECT_EQ(holmAdjusted({0.6, 0.7}), (std::vector<double>{1.0, 1.0}));
}

TEST(MannWhitney, RunsNeededGrowAsTheSeparationShrinks) {
  double level = 0.05 / 6;
  // Complete separation: z = n/2 sqrt(12 / (2n + 1)); n = 5 gives p = 0.009, n = 6 p = 0.004.
  EXPECT_EQ(perSideNeeded(1.0, level, 1), 6u);
  EXPECT_EQ(perSideNeeded(0.0, level, 1), 6u) << "either direction";
  EXPECT_EQ(perSideNeeded(1.0, level, 9), 9u) << "never below the floor given";
  auto some = perSideNeeded(0.8, level, 1), less = perSideNeeded(0.65, level, 1);
  ASSERT_TRUE(some && less);
  EXPECT_GT(*less, *some);
  EXPECT_FALSE(perSideNeeded(0.5, level, 1)) << "no separation: no number of runs";
}

TEST(MannWhitney, RankSumEqualsPairCountOnRandomData) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> value(0, 9);  // small range: many ties
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<double> a(3 + size_t(trial % 7)), b(4 + size_t(trial % 5));
    for (auto& v : a) v = value(rng);
    for (auto& v : b) v = value(rng);
    EXPECT_DOUBLE_EQ(mannWhitneyU(a, b).u, pairCountU(a, b));
  }
}

TEST(CompareStats, MedianAndRobustSpreadIgnoreOneOutlier) {
  EXPECT_EQ(medianOf({3, 1, 2}), 2.0);
  EXPECT_EQ(medianOf({4, 1, 3, 2}), 2.5);
  EXPECT_NEAR(robustSpread({10, 11, 9, 10, 1000}), 1.4826, 1e-12);  // MAD 1
}

// Timing-like samples: a base time with multiplicative noise and rare preemption spikes.
std::vector<double> noisyTimes(std::mt19937& rng, double base, size_t count, double noise) {
  std::normal_distribution<double> jitter(0.0, noise);
  std::uniform_real_distribution<double> spike(0.0, 1.0);
  std::vector<double> out;
  for (size_t i = 0; i < count; ++i) out.push_back(base * (1.0 + jitter(rng)) * (spike(rng) < 0.03 ? 1.5 : 1.0));
  return out;
}

TimingSamples twoPasses(std::mt19937& rng, double slowdown, size_t count, double noise) {
  return {{"gtao", noisyTimes(rng, 2.0 * slowdown, count, noise)}, {"spatial", noisyTimes(rng, 1.0, count, noise)}};
}

TEST(Compare, SameDistributionIsCalledSameAlmostAlways) {
  std::mt19937 rng(2024);
  CompareOptions options;
  int alarms = 0;
  const int trials = 400;
  for (int t = 0; t < trials; ++t) {
    auto c = compareTimings(twoPasses(rng, 1.0, 30, 0.03), twoPasses(rng, 1.0, 30, 0.03), options);
    EXPECT_EQ(c.level, Level::Samples) << "one run a side";
    for (const auto& p : c.passes) ASSERT_NE(p.verdict, Verdict::Unknown) << p.name;  // 30 samples are enough
    alarms += c.significantSlowdown() || c.passes[0].verdict == Verdict::Faster || c.passes[1].verdict == Verdict::Faster;
  }
  // alpha = 5% family-wise (Holm), and the effect threshold on top: twice the spread, 6% here,
  // against medians of 30 that differ by about 1% (sd): alarms are much rarer than alpha.
  EXPECT_LE(alarms, trials / 100);
}

TEST(Compare, TenPercentSlowdownIsCalledSlower) {
  std::mt19937 rng(99);
  auto c = compareTimings(twoPasses(rng, 1.0, 30, 0.02), twoPasses(rng, 1.1, 30, 0.02), CompareOptions{});
  ASSERT_EQ(c.passes.size(), 2u);
  EXPECT_EQ(c.passes[0].name, "gtao");
  EXPECT_EQ(c.passes[0].verdict, Verdict::Slower);
  EXPECT_NEAR(c.passes[0].ratio(), 1.10, 0.02);
  EXPECT_EQ(c.passes[1].verdict, Verdict::Same);
  EXPECT_TRUE(c.significantSlowdown());
  auto reverse = compareTimings(twoPasses(rng, 1.1, 30, 0.02), twoPasses(rng, 1.0, 30, 0.02), CompareOptions{});
  EXPECT_EQ(reverse.passes[0].verdict, Verdict::Faster);
  EXPECT_FALSE(reverse.significantSlowdown());
}

TEST(Compare, SignificantButTinyChangeIsSame) {
  std::mt19937 rng(5);
  // 1% slower with 0.1% noise: the test is sure, but 1% is under the 2% minimum effect.
  auto c = compareTimings(twoPasses(rng, 1.0, 40, 0.001), twoPasses(rng, 1.01, 40, 0.001), CompareOptions{});
  EXPECT_LT(c.passes[0].pValue, 1e-6);
  EXPECT_EQ(c.passes[0].verdict, Verdict::Same);
}

TEST(Compare, SubMicrosecondShiftOfAMicrosecondPassIsSame) {
  // The H100 case of compare_README.md: a 7.6 us pass, 0.1 % spread, 2.5 % (0.19 us) slower.
  std::mt19937 rng(17);
  TimingSamples base{{"temporal", noisyTimes(rng, 0.0076, 20, 0.001)}};
  TimingSamples shifted{{"temporal", noisyTimes(rng, 0.0076 * 1.025, 20, 0.001)}};
  auto c = compareTimings(base, shifted, CompareOptions{});
  EXPECT_LT(c.passes[0].pValue, 1e-4);
  EXPECT_NEAR(c.passes[0].threshold, std::log1p(0.001 / c.passes[0].baselineMedian), 1e-12);
  EXPECT_EQ(c.passes[0].verdict, Verdict::Same);
  CompareOptions noFloor;
  noFloor.minEffectMs = 0;
  EXPECT_EQ(compareTimings(base, shifted, noFloor).passes[0].verdict, Verdict::Slower);
  // Several microseconds still count: one extra GTAO slice on a 9 us pass adds about 3 us.
  TimingSamples slice{{"temporal", noisyTimes(rng, 0.0076 * 1.4, 20, 0.001)}};
  EXPECT_EQ(compareTimings(base, slice, CompareOptions{}).passes[0].verdict, Verdict::Slower);
}

TEST(Compare, ThresholdGrowsWithTheBaselineSpread) {
  std::mt19937 rng(11);
  auto c = compareTimings(twoPasses(rng, 1.0, 50, 0.05), twoPasses(rng, 1.0, 50, 0.001), CompareOptions{});
  EXPECT_GT(c.passes[0].threshold, 0.07);  // about 2 x 5%, well above the 2% floor
  EXPECT_NEAR(c.passes[0].threshold, 2 * c.passes[0].baselineSpread, 1e-12);
}

TEST(Compare, ThresholdGrowsWithTheNewRunsSpread) {
  std::mt19937 rng(12);
  auto c = compareTimings(twoPasses(rng, 1.0, 50, 0.001), twoPasses(rng, 1.0, 50, 0.05), CompareOptions{});
  EXPECT_LT(c.passes[0].baselineSpread, 0.002);
  EXPECT_GT(c.passes[0].threshold, 0.07);
  EXPECT_NEAR(c.passes[0].threshold, 2 * c.passes[0].newSpread, 1e-12);
}

// A run's samples share the run's own shift (CPU frequency, the machine's other load, memory
// placement): one factor drawn per run, then per-sample noise.
TimingSamples runWithShift(std::mt19937& rng, double slowdown, double runToRun) {
  std::normal_distribution<double> shift(0.0, runToRun);
  double factor = std::exp(shift(rng));
  return twoPasses(rng, slowdown * factor, 40, 0.02);
}

SideTimings runs(std::mt19937& rng, size_t count, double slowdown, double runToRun) {
  SideTimings side;
  for (size_t i = 0; i < count; ++i) side.runs.push_back({fmt::format("run{}", i), runWithShift(rng, slowdown, runToRun)});
  return side;
}

TEST(CompareRuns, RunToRunShiftsFoolTheWithinRunTestButNotTheRunLevelOne) {
  // Runs of one build whose level moves by 5% (sd) from run to run, as separate processes on a
  // shared machine do. One run a side: 40 samples a side see two levels and call it a change
  // (rule 4's spread threshold absorbs some, not all). Ten runs a side: each run is one value,
  // and the test sees the run-to-run variation it has to beat.
  std::mt19937 rng(77);
  CompareOptions options;
  int withinRunAlarms = 0, runLevelAlarms = 0, runLevelAllSame = 0;
  const int trials = 100;
  for (int t = 0; t < trials; ++t) {
    auto one = compareTimings(runWithShift(rng, 1.0, 0.05), runWithShift(rng, 1.0, 0.05), options);
    withinRunAlarms += one.significantSlowdown() || one.passes[0].verdict == Verdict::Faster;
    auto many = compareTimings(runs(rng, 10, 1.0, 0.05), runs(rng, 10, 1.0, 0.05), options);
    ASSERT_EQ(many.level, Level::Runs);
    EXPECT_EQ(many.passes[0].baselineCount, 10u) << "one value per run";
    runLevelAlarms += many.significantSlowdown() || many.passes[0].verdict == Verdict::Faster;
    runLevelAllSame += std::all_of(many.passes.begin(), many.passes.end(), [](const auto& p) { return p.verdict == Verdict::Same; });
  }
  EXPECT_GE(withinRunAlarms, 30) << "the within-run test cries wolf on run-to-run shifts (58 of 100 with this seed)";
  EXPECT_LE(runLevelAlarms, trials * 5 / 100) << "alpha = 5%, family-wise";
  EXPECT_GE(runLevelAllSame, trials * 90 / 100);
}

TEST(CompareRuns, ASlowdownLargerThanTheRunToRunNoiseIsSlower) {
  std::mt19937 rng(78);
  auto c = compareTimings(runs(rng, 10, 1.0, 0.03), runs(rng, 10, 1.3, 0.03), CompareOptions{});
  ASSERT_EQ(c.level, Level::Runs);
  EXPECT_EQ(c.passes[0].verdict, Verdict::Slower);
  EXPECT_TRUE(c.passes[0].exact);
  EXPECT_LT(c.passes[0].pHolm, 0.001);
  EXPECT_EQ(c.passes[1].verdict, Verdict::Same);
  EXPECT_TRUE(c.significantSlowdown());
}

TEST(CompareRuns, OnANoisyMachineRunsConfirmWhatTheSpreadAloneWouldCallSame) {
  // Run levels move by 30% (sd) from run to run, as on a loaded 2-core machine. Twice that spread
  // is a threshold of x1.8; a real x1.6 is below it. Within-run samples would have to call it
  // `same` (rule 4); ten runs a side show it beyond their own variation, so it is `slower`.
  std::mt19937 rng(81);
  CompareOptions options;
  int found = 0, belowSpread = 0, alarms = 0, allSame = 0;
  const int trials = 50;
  for (int t = 0; t < trials; ++t) {
    auto slow = compareTimings(runs(rng, 10, 1.0, 0.3), runs(rng, 10, 1.6, 0.3), options);
    found += slow.passes[0].verdict == Verdict::Slower;
    belowSpread += slow.passes[0].verdict == Verdict::Slower && slow.passes[0].logRatio < slow.passes[0].threshold;
    auto same = compareTimings(runs(rng, 10, 1.0, 0.3), runs(rng, 10, 1.0, 0.3), options);
    alarms += same.significantSlowdown() || same.passes[0].verdict == Verdict::Faster;
    allSame += std::all_of(same.passes.begin(), same.passes.end(), [](const auto& p) { return p.verdict == Verdict::Same; });
  }
  EXPECT_GE(found, trials * 7 / 10);
  EXPECT_GE(belowSpread, trials / 4) << "slower although under twice the spread";
  EXPECT_LE(alarms, trials * 5 / 100) << "alpha = 5%, family-wise";
  EXPECT_GE(allSame, trials * 9 / 10) << "the same build is `same`, not `unknown`, however noisy";
}

TEST(CompareRuns, ChangesAreLogRatiosSoBothDirectionsAreEquallyFar) {
  // The example: a run 2.16x slower than another. As a percent it is +116% one way and
  // -54% the other; as a log-ratio +-0.77, and the verdicts mirror.
  std::mt19937 rng(79);
  auto fast = runs(rng, 6, 1.0, 0.02), slow = runs(rng, 6, 2.16, 0.02);
  auto up = compareTimings(fast, slow, CompareOptions{}), down = compareTimings(slow, fast, CompareOptions{});
  ASSERT_EQ(up.passes.size(), down.passes.size());
  for (size_t i = 0; i < up.passes.size(); ++i) {
    EXPECT_EQ(up.passes[i].logRatio, -down.passes[i].logRatio) << up.passes[i].name;
    EXPECT_DOUBLE_EQ(up.passes[i].threshold, down.passes[i].threshold) << up.passes[i].name;
    EXPECT_DOUBLE_EQ(up.passes[i].pHolm, down.passes[i].pHolm) << up.passes[i].name;
  }
  EXPECT_EQ(up.passes[0].verdict, Verdict::Slower);
  EXPECT_EQ(down.passes[0].verdict, Verdict::Faster);
  EXPECT_NEAR(up.passes[0].logRatio, std::log(2.16), 0.05);
}

TEST(CompareRuns, TooFewRunsSayHowManyMoreAndTheFewestThatCanTell) {
  std::mt19937 rng(80);
  // Three judged names (gtao, spatial, and a total when report.json gives one; here two) at
  // alpha 0.05: the first Holm step is 0.025, which 4 a side (2/70 = 0.029) cannot reach; 5 can.
  auto c = compareTimings(runs(rng, 3, 1.0, 0.02), runs(rng, 3, 1.5, 0.02), CompareOptions{});
  EXPECT_EQ(c.level, Level::Runs);
  EXPECT_EQ(c.judgedNames, 2u);
  EXPECT_EQ(c.fewestPerSide, 5u);
  EXPECT_EQ(c.passes[0].verdict, Verdict::Unknown);
  EXPECT_EQ(c.passes[0].moreNeeded, 2u);
  auto table = comparisonTable(c);
  EXPECT_NE(table.find("unknown — need 2 more runs a side"), std::string::npos) << table;
  EXPECT_NE(table.find("values: one per run"), std::string::npos) << table;
  EXPECT_NE(table.find("5 a side at the least"), std::string::npos) << table;
  auto json = comparisonJson(c, CompareOptions{});
  EXPECT_EQ(json["level"], "runs");
  EXPECT_EQ(json["fewest_per_side"], 5);
  EXPECT_EQ(json["baseline"]["runs"], 3);
  // One run a side: the fallback says so in the table and the JSON.
  auto one = compareTimings(runWithShift(rng, 1.0, 0.0), runWithShift(rng, 1.0, 0.0), CompareOptions{});
  EXPECT_EQ(comparisonJson(one, CompareOptions{})["level"], "samples");
  EXPECT_NE(comparisonTable(one).find("within-run samples"), std::string::npos) << comparisonTable(one);
}

// Three real lavapipe runs of one build (tests/support/data/compare-lavapipe-disturbed, from pair 1 of
// experiment 9c in bench/RESULTS.md): in the second run another process took one of the two cores
// for about 15 of the 40 samples, which then took twice as long (compare_README.md, rule 4). The
// third ran one GTAO slice more.
TimingSamples disturbedExperimentRun(const std::string& name) {
  return loadTimingSamples(std::filesystem::path(AOR_SOURCE_DIR) / "tests/support/data/compare-lavapipe-disturbed" / (name + ".json"));
}

TEST(Compare, ARunThatLostACoreForAWhileIsNotASlowdown) {
  CompareOptions options;
  auto c = compareTimings(disturbedExperimentRun("baseline"), disturbedExperimentRun("same-build"), options);
  EXPECT_FALSE(c.significantSlowdown());
  int alarmsByBaselineSpreadAlone = 0;
  for (const auto& p : c.passes) {
    if (p.judged) {
      EXPECT_EQ(p.verdict, Verdict::Same) << p.name;
    }
    alarmsByBaselineSpreadAlone += p.judged && p.pHolm <= options.alpha &&
                                   p.logRatio >= std::max(std::log1p(options.minEffect), options.spreadMultiple * p.baselineSpread);
  }
  // What the rule is for: judged against the baseline's spread alone, this pair was a false alarm
  // (spatial_columns +10 %, spatial +11 %, total +32 %).
  EXPECT_GE(alarmsByBaselineSpreadAlone, 2);
}

TEST(Compare, OneExtraSliceIsStillSlowerOnTheSameNoisyMachine) {
  auto c = compareTimings(disturbedExperimentRun("baseline"), disturbedExperimentRun("extra-slice"), CompareOptions{});
  EXPECT_TRUE(c.significantSlowdown());
  auto gtao = std::find_if(c.passes.begin(), c.passes.end(), [](const auto& p) { return p.name == "gtao"; });
  ASSERT_NE(gtao, c.passes.end());
  EXPECT_EQ(gtao->verdict, Verdict::Slower);
  EXPECT_GT(gtao->ratio(), 1.15);
}

TEST(Compare, TooFewOrInconclusiveSamplesAreUnknown) {
  // 3 a side can give no p below 2/20 = 0.1: unknown however far apart, and 4 a side would do.
  TimingSamples few{{"gtao", {1.0, 1.1, 0.9}}};
  TimingSamples fewSlower{{"gtao", {2.0, 2.1, 1.9}}};
  auto tooFew = compareTimings(few, fewSlower, CompareOptions{});
  EXPECT_EQ(tooFew.fewestPerSide, 4u);
  EXPECT_EQ(tooFew.passes[0].verdict, Verdict::Unknown);
  EXPECT_EQ(tooFew.passes[0].moreNeeded, 1u);
  EXPECT_NE(comparisonTable(tooFew).find("unknown — need 1 more sample a side"), std::string::npos) << comparisonTable(tooFew);
  // A tight baseline and a median 8% higher, but two new samples are the fastest of all: the
  // change is over the threshold, the test cannot confirm it.
  TimingSamples tight{{"gtao", {1.00, 1.01, 1.02, 1.03, 1.04}}};
  TimingSamples mixed{{"gtao", {0.99, 1.00, 1.10, 1.11, 1.12}}};
  auto c = compareTimings(tight, mixed, CompareOptions{});
  EXPECT_GT(c.passes[0].logRatio, c.passes[0].threshold);
  EXPECT_GT(c.passes[0].pHolm, CompareOptions{}.alpha);
  EXPECT_EQ(c.passes[0].verdict, Verdict::Unknown);
  ASSERT_TRUE(c.passes[0].moreNeeded.has_value());
  EXPECT_GE(*c.passes[0].moreNeeded, 1u);
  EXPECT_STREQ(verdictText(Verdict::Unknown), "unknown");
  auto json = comparisonJson(c, CompareOptions{});
  EXPECT_EQ(json["passes"][0]["verdict"], "unknown");
  EXPECT_EQ(json["passes"][0]["more_needed_per_side"], *c.passes[0].moreNeeded);
  EXPECT_TRUE(c.unknownJudged());
  EXPECT_FALSE(c.fails(CompareOptions{}));
  CompareOptions strict;
  strict.failOnUnknown = true;
  EXPECT_TRUE(c.fails(strict));
}

TEST(Compare, NamesInOnlyOneRunAreListedNotCompared) {
  TimingSamples a{{"gtao", {1, 1, 1, 1, 1}}, {"spatial", {1, 1, 1, 1, 1}}};
  TimingSamples b{{"gtao", {1, 1, 1, 1, 1}}, {"temporal", {1, 1, 1, 1, 1}}};
  auto c = compareTimings(a, b, CompareOptions{});
  ASSERT_EQ(c.passes.size(), 1u);
  EXPECT_EQ(c.onlyInBaseline, std::vector<std::string>{"spatial"});
  EXPECT_EQ(c.onlyInNew, std::vector<std::string>{"temporal"});
  auto json = comparisonJson(c, CompareOptions{});
  EXPECT_EQ(json["passes"][0]["verdict"], "same");
  EXPECT_EQ(json["significant_slowdown"], false);
}

TEST(Compare, HostCopiesAreShownButNotJudgedUnlessAsked) {
  std::vector<double> ones(10, 1.0), twos(10, 2.0);
  TimingSamples base{{"gtao", ones}, {"readback", ones, true}};
  TimingSamples slowCopy{{"gtao", ones}, {"readback", twos, true}};
  auto c = compareTimings(base, slowCopy, CompareOptions{});
  ASSERT_EQ(c.passes.size(), 2u);
  EXPECT_TRUE(c.passes[0].judged);
  EXPECT_FALSE(c.passes[1].judged);
  EXPECT_EQ(c.passes[1].verdict, Verdict::Slower);  // still measured and shown
  EXPECT_FALSE(c.significantSlowdown());
  EXPECT_EQ(c.judgedNames, 1u) << "Holm's family is the judged names only";
  EXPECT_EQ(c.passes[0].pHolm, c.passes[0].pValue);
  EXPECT_NE(comparisonTable(c).find("slower (host copy: not judged)"), std::string::npos) << comparisonTable(c);
  EXPECT_EQ(comparisonJson(c, CompareOptions{})["passes"][1]["judged"], false);

  CompareOptions judgeCopies;
  judgeCopies.judgeHostCopies = true;
  auto judged = compareTimings(base, slowCopy, judgeCopies);
  EXPECT_TRUE(judged.passes[1].judged);
  EXPECT_TRUE(judged.significantSlowdown());
  EXPECT_EQ(judged.judgedNames, 2u);
}

// One scratch folder per process, emptied once (scratchDir empties on every call); file names differ per test.
const std::filesystem::path& scratch() {
  static const auto dir = test::scratchDir("compare");
  return dir;
}

std::filesystem::path writeFile(const std::string& name, const nlohmann::json& json) {
  auto path = scratch() / name;
  std::ofstream(path) << json.dump();
  return path;
}

nlohmann::json reportWith(const std::vector<double>& gtao, const std::vector<double>& spatial) {
  return {{"tool", "aoreplay"},
          {"passes", {{{"name", "gtao"}, {"gpu_ms", {{"median", 0}, {"samples", gtao}}}},
                      {{"name", "spatial"}, {"gpu_ms", {{"median", 0}, {"samples", spatial}}}}}}};
}

TEST(CompareInput, ReportJsonGivesPassesAndTheirPerRunTotal) {
  auto path = writeFile("report.json", reportWith({1, 2, 3}, {0.5, 0.25, 0.125}));
  auto samples = loadTimingSamples(path);
  ASSERT_EQ(samples.size(), 3u);
  EXPECT_EQ(samples[0].name, "gtao");
  EXPECT_EQ(samples[2].name, "total");
  EXPECT_EQ(samples[2].samples, (std::vector<double>{1.5, 2.25, 3.125}));
}

TEST(CompareInput, ReportJsonMarksHostCopiesAndLeavesThemOutOfTheTotal) {
  auto report = reportWith({1, 2, 3}, {0.5, 0.25, 0.125});
  report["passes"].push_back({{"name", "readback"}, {"gpu_ms", {{"median", 0}, {"samples", {10, 20, 30}}}}});
  report["passes"].push_back({{"name", "upload"}, {"gpu_ms", {{"median", 0}, {"samples", {40, 50, 60}}}}});
  auto samples = loadTimingSamples(writeFile("copies.json", report));
  ASSERT_EQ(samples.size(), 5u);
  EXPECT_FALSE(samples[0].hostCopy);
  EXPECT_TRUE(samples[2].hostCopy);
  EXPECT_TRUE(samples[3].hostCopy);
  EXPECT_EQ(samples[4].name, "total");
  EXPECT_FALSE(samples[4].hostCopy);
  EXPECT_EQ(samples[4].samples, (std::vector<double>{1.5, 2.25, 3.125})) << "the compute passes only";
}

TEST(CompareInput, ReportJsonTotalIsSummedPerRepetitionOfEachFrame) {
  // Two frames, two timed repetitions each; temporal ran only in the second frame. The samples are
  // frame-major: gtao's are frame 0's two, then frame 1's two.
  nlohmann::json report{{"tool", "aoreplay"},
                        {"run", {{"repeat", 2}}},
                        {"passes", {{{"name", "gtao"}, {"gpu_ms", {{"samples", {1, 2, 3, 4}}}}},
                                    {{"name", "temporal"}, {"gpu_ms", {{"samples", {10, 20}}}}},
                                    {{"name", "upload"}, {"gpu_ms", {{"samples", {100, 100, 100, 100}}}}}}},
                        {"frames", {{{"gpu_ms_median", {{"gtao", 1.5}, {"upload", 100}}}},
                                    {{"gpu_ms_median", {{"gtao", 3.5}, {"temporal", 15}, {"upload", 100}}}}}}};
  auto samples = loadTimingSamples(writeFile("frames.json", report));
  ASSERT_EQ(samples.size(), 4u);
  EXPECT_EQ(samples[3].name, "total");
  EXPECT_EQ(samples[3].samples, (std::vector<double>{1, 2, 13, 24}));
  EXPECT_EQ(samples[3].runValue(), 7.5) << "the median per-repetition sum, as gpu_ms_total_median";
  EXPECT_EQ(samples[0].runValue(), 2.5) << "a pass's value is its median";

  auto broken = [&](const char* file, auto change, const std::string& field) {
    auto bad = report;
    change(bad);
    try {
      loadTimingSamples(writeFile(file, bad));
      ADD_FAILURE() << file << ": no error";
    } catch (const InputError& e) {
      EXPECT_EQ(e.field, field) << file << ": " << e.what();
    }
  };
  broken("extra-sample.json", [](auto& r) { r["passes"][1]["gpu_ms"]["samples"].push_back(30); }, "passes[1].gpu_ms.samples");
  broken("missing-sample.json", [](auto& r) { r["passes"][0]["gpu_ms"]["samples"].erase(3); }, "passes[0].gpu_ms.samples");
  broken("unknown-pass.json", [](auto& r) { r["frames"][0]["gpu_ms_median"]["nope"] = 1; }, "frames[0].gpu_ms_median.nope");
  broken("no-repeat.json", [](auto& r) { r.erase("run"); }, "run.repeat");
  broken("no-frame-passes.json", [](auto& r) { r["frames"][1].erase("gpu_ms_median"); }, "frames[1].gpu_ms_median");
  // A pass listed twice once added its samples into the total twice (x1.15 on a real report).
  broken("pass-twice.json", [](auto& r) { r["passes"].push_back(r["passes"][0]); }, "passes[3].name");
}

TEST(CompareInput, AFolderIsItsReportJsonFilesOnePerRun) {
  auto folder = scratch() / "side";
  for (const char* run : {"b/02", "a/01", "a/nested/03", ".r.tmp-99"}) {
    std::filesystem::create_directories(folder / run);
    std::ofstream(folder / run / "report.json") << reportWith({1, 2, 3}, {1, 1, 1}).dump();
  }
  std::ofstream(folder / "a" / "01" / "trace.json") << "{}";
  auto side = loadSide(folder);
  ASSERT_EQ(side.runs.size(), 3u) << "the hidden staging folder is skipped";
  EXPECT_EQ(side.source, folder.string());
  EXPECT_EQ(side.runs[0].source, (folder / "a" / "01" / "report.json").string());
  EXPECT_EQ(side.runs[1].source, (folder / "a" / "nested" / "03" / "report.json").string());
  EXPECT_EQ(side.runs[2].source, (folder / "b" / "02" / "report.json").string());
  EXPECT_EQ(loadSide(folder / "a" / "01" / "report.json").runs.size(), 1u) << "a file is one run";
  std::filesystem::create_directories(scratch() / "empty-side");
  try {
    loadSide(scratch() / "empty-side");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file, (scratch() / "empty-side").string());
    EXPECT_NE(std::string(e.what()).find("holds no report.json"), std::string::npos) << e.what();
  }
}

TEST(CompareInput, GoogleBenchmarkJsonUsesIterationsInMilliseconds) {
  nlohmann::json doc{{"context", {}},
                     {"benchmarks",
                      {{{"name", "BM_Gtao/repeats:2"}, {"run_name", "BM_Gtao"}, {"run_type", "iteration"},
                        {"real_time", 1500.0}, {"time_unit", "us"}},
                       {{"name", "BM_Gtao/repeats:2"}, {"run_name", "BM_Gtao"}, {"run_type", "iteration"},
                        {"real_time", 2.5}, {"time_unit", "ms"}},
                       {{"name", "BM_Gtao_median"}, {"run_name", "BM_Gtao"}, {"run_type", "aggregate"},
                        {"real_time", 2.0}, {"time_unit", "ms"}}}}};
  auto samples = loadTimingSamples(writeFile("bench.json", doc));
  ASSERT_EQ(samples.size(), 1u);
  EXPECT_EQ(samples[0].name, "BM_Gtao");
  EXPECT_EQ(samples[0].samples, (std::vector<double>{1.5, 2.5}));
}

TEST(CompareInput, BenchmarkNamesMatchAcrossRepetitionCounts) {
  auto bench = [&](const char* file, const char* runName, int n) {
    nlohmann::json entries = nlohmann::json::array();
    for (int i = 0; i < n; ++i)
      entries.push_back({{"name", runName}, {"run_name", runName}, {"run_type", "iteration"}, {"real_time", 1.0 + i}, {"time_unit", "ms"}});
    return loadTimingSamples(writeFile(file, {{"context", {}}, {"benchmarks", entries}}));
  };
  auto ten = bench("ten.json", "gtao/s3x3/640x360/iterations:1/repeats:10/manual_time", 10);
  auto twenty = bench("twenty.json", "gtao/s3x3/640x360/iterations:1/repeats:20/manual_time", 20);
  auto last = bench("last.json", "gtao/s3x3/640x360/repeats:5", 5);
  ASSERT_EQ(ten.size(), 1u);
  EXPECT_EQ(ten[0].name, "gtao/s3x3/640x360/iterations:1/manual_time");
  EXPECT_EQ(twenty[0].name, ten[0].name);
  EXPECT_EQ(twenty[0].samples.size(), 20u);
  EXPECT_EQ(last[0].name, "gtao/s3x3/640x360");
  EXPECT_FALSE(ten[0].hostCopy);
  EXPECT_TRUE(bench("copy.json", "readback/s3x3/640x360/repeats:5", 5)[0].hostCopy);
  EXPECT_FALSE(bench("pipeline.json", "pipeline/s3x3/640x360/repeats:5", 5)[0].hostCopy);
}

TEST(CompareInput, BadInputNamesTheFileAndField) {
  auto old = writeFile("old.json", {{"tool", "aoreplay"}, {"passes", {{{"name", "gtao"}, {"gpu_ms", {{"median", 1}}}}}}});
  try {
    loadTimingSamples(old);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file, old.string());
    EXPECT_EQ(e.field, "passes[0].gpu_ms.samples");
  }
  auto negative = writeFile("negative.json", reportWith({1, -2, 3}, {1, 1, 1}));
  try {
    loadTimingSamples(negative);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field, "passes[0].gpu_ms.samples[1]");
  }
  EXPECT_THROW(loadTimingSamples(writeFile("other.json", {{"x", 1}})), InputError);
  EXPECT_THROW(loadTimingSamples(scratch() / "missing.json"), InputError);
}

TEST(CompareCommand, ExitCodesTableAndJson) {
  std::mt19937 rng(3);
  auto base = writeFile("base.json", reportWith(noisyTimes(rng, 2, 20, 0.01), noisyTimes(rng, 1, 20, 0.01)));
  auto same = writeFile("same.json", reportWith(noisyTimes(rng, 2, 20, 0.01), noisyTimes(rng, 1, 20, 0.01)));
  auto slower = writeFile("slower.json", reportWith(noisyTimes(rng, 2.3, 20, 0.01), noisyTimes(rng, 1, 20, 0.01)));
  auto json = scratch() / "verdicts.json";

  auto r = test::runAoreplay("compare " + base.string() + " " + same.string());
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("gtao"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("slower"), std::string::npos) << r.output;

  r = test::runAoreplay("compare " + base.string() + " " + slower.string() + " --json " + json.string());
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("slower"), std::string::npos) << r.output;
  auto verdicts = nlohmann::json::parse(std::ifstream(json));
  EXPECT_EQ(verdicts["passes"][0]["name"], "gtao");
  EXPECT_EQ(verdicts["passes"][0]["verdict"], "slower");
  EXPECT_EQ(verdicts["passes"][1]["verdict"], "same");

  r = test::runAoreplay("compare " + slower.string() + " " + base.string());
  EXPECT_EQ(r.exitCode, 0) << r.output;  // faster never fails
  EXPECT_NE(r.output.find("faster"), std::string::npos) << r.output;

  r = test::runAoreplay("compare " + base.string() + " " + slower.string() + " --ignore '^gtao$' --ignore '^total$'");
  EXPECT_EQ(r.exitCode, 0) << r.output;  // the slow pass is ignored
  EXPECT_EQ(r.output.find("gtao"), std::string::npos) << r.output;
  r = test::runAoreplay("compare " + base.string() + " " + slower.string() + " --ignore '('");
  EXPECT_EQ(r.exitCode, 2) << r.output;

  r = test::runAoreplay("compare " + base.string() + " " + (scratch() / "nope.json").string());
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("nope.json"), std::string::npos) << r.output;

  // An unwritable --json is named, exits 2, and leaves nothing behind.
  auto underAFile = base / "verdicts.json";
  r = test::runAoreplay("compare " + base.string() + " " + same.string() + " --json " + underAFile.string());
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find(underAFile.string()), std::string::npos) << r.output;
  r = test::runAoreplay("compare " + base.string() + " " + same.string() + " --json " + scratch().string());
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("names a folder"), std::string::npos) << r.output;
  for (const auto& entry : std::filesystem::directory_iterator(scratch()))
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
}

// A folder of runs for each side: each run's gtao around `gtaoMs`, its own level drawn per run.
std::filesystem::path runFolder(const std::string& name, std::mt19937& rng, size_t count, double gtaoMs) {
  auto folder = scratch() / name;
  std::normal_distribution<double> level(0.0, 0.01);
  for (size_t i = 0; i < count; ++i) {
    double factor = std::exp(level(rng));
    auto run = folder / fmt::format("{:02d}", i + 1);
    std::filesystem::create_directories(run);
    std::ofstream(run / "report.json")
        << reportWith(noisyTimes(rng, gtaoMs * factor, 20, 0.01), noisyTimes(rng, factor, 20, 0.01)).dump();
  }
  return folder;
}

TEST(CompareCommand, FoldersAreJudgedRunByRun) {
  std::mt19937 rng(6);
  auto base = runFolder("runs-base", rng, 6, 2.0), same = runFolder("runs-same", rng, 6, 2.0);
  auto slower = runFolder("runs-slower", rng, 6, 2.4), few = runFolder("runs-few", rng, 2, 2.4);
  auto json = scratch() / "runs-verdicts.json";

  auto r = test::runAoreplay("compare " + base.string() + " " + same.string());
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("(6 runs)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("values: one per run"), std::string::npos) << r.output;

  r = test::runAoreplay("compare " + base.string() + " " + slower.string() + " --json " + json.string());
  EXPECT_EQ(r.exitCode, 1) << r.output;
  auto verdicts = nlohmann::json::parse(std::ifstream(json));
  EXPECT_EQ(verdicts["level"], "runs");
  EXPECT_EQ(verdicts["passes"][0]["name"], "gtao");
  EXPECT_EQ(verdicts["passes"][0]["verdict"], "slower");
  EXPECT_EQ(verdicts["passes"][0]["baseline_count"], 6);
  EXPECT_EQ(verdicts["passes"][0]["p_exact"], true);
  EXPECT_NEAR(verdicts["passes"][0]["ratio"].get<double>(), 1.2, 0.03);

  // Two runs a side cannot tell: unknown, which fails only with --fail-on-unknown.
  r = test::runAoreplay("compare " + few.string() + " " + slower.string());
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("unknown — need 3 more runs a side"), std::string::npos) << r.output;
  r = test::runAoreplay("compare " + few.string() + " " + slower.string() + " --fail-on-unknown");
  EXPECT_EQ(r.exitCode, 1) << r.output;

  // A bad run inside a folder is named, file and field.
  auto bad = runFolder("runs-bad", rng, 5, 2.0);
  std::ofstream(bad / "03" / "report.json") << reportWith({1, -2, 3}, {1, 1, 1}).dump();
  r = test::runAoreplay("compare " + base.string() + " " + bad.string());
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find((bad / "03" / "report.json").string()), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("passes[0].gpu_ms.samples[1]"), std::string::npos) << r.output;
  std::filesystem::create_directories(scratch() / "runs-none");
  r = test::runAoreplay("compare " + base.string() + " " + (scratch() / "runs-none").string());
  EXPECT_EQ(r.exitCode, 2) << r.output;
}

TEST(CompareCommand, ASlowerHostCopyFailsOnlyWhenAskedTo) {
  std::mt19937 rng(4);
  auto withReadback = [&](double readbackMs) {
    auto report = reportWith(noisyTimes(rng, 2, 20, 0.01), noisyTimes(rng, 1, 20, 0.01));
    report["passes"].push_back({{"name", "readback"}, {"gpu_ms", {{"median", 0}, {"samples", noisyTimes(rng, readbackMs, 20, 0.01)}}}});
    return report;
  };
  auto base = writeFile("copy-base.json", withReadback(0.1));
  auto slowCopy = writeFile("copy-slow.json", withReadback(0.2));
  auto r = test::runAoreplay("compare " + base.string() + " " + slowCopy.string());
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("slower (host copy: not judged)"), std::string::npos) << r.output;
  r = test::runAoreplay("compare " + base.string() + " " + slowCopy.string() + " --judge-host-copies");
  EXPECT_EQ(r.exitCode, 1) << r.output;
}

}  // namespace
}  // namespace aor
