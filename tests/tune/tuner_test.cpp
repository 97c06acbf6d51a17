// The search behind `aoreplay tune`, on objectives with known minima (no GPU).
#include "tune/tuner.h"

#include "tune/cross_validation.h"

#include <cmath>

#include <gtest/gtest.h>

namespace aor {
namespace {

// A tilted bowl with its minimum at (0.3, 2.5), off the grid's cell centres.
TuneMeasure bowl(const std::vector<double>& v) {
  double a = v[0] - 0.3, b = (v[1] - 2.5) / 4.0;
  return {a * a + b * b + 0.1 * a * b, 0};
}

TuneProblem bowlProblem() {
  TuneProblem p;
  p.dimensions = {{"a", 0, 1, false, false, 0.9}, {"b", 0, 16, false, false, 12}};
  p.evaluate = bowl;
  p.maxEvaluations = 60;
  return p;
}

TEST(Tuner, FindsTheMinimumOfABowlFromAFarStart) {
  TuneResult r = tune(bowlProblem());
  ASSERT_GE(r.best, 0);
  const auto& best = r.evaluations[size_t(r.best)];
  EXPECT_NEAR(best.values[0], 0.3, 0.02);
  EXPECT_NEAR(best.values[1], 2.5, 0.2);
  EXPECT_LT(best.measure.objective, r.evaluations[0].measure.objective / 100);
  EXPECT_EQ(r.evaluations[0].phase, "start");
  EXPECT_EQ(r.evaluations[0].values, (std::vector<double>{0.9, 12}));
  EXPECT_LE(int(r.evaluations.size()), 60);
}

TEST(Tuner, SameProblemSameEvaluationsInTheSameOrder) {
  TuneResult a = tune(bowlProblem()), b = tune(bowlProblem());
  ASSERT_EQ(a.evaluations.size(), b.evaluations.size());
  for (size_t i = 0; i < a.evaluations.size(); ++i) {
    EXPECT_EQ(a.evaluations[i].values, b.evaluations[i].values) << i;
    EXPECT_EQ(a.evaluations[i].phase, b.evaluations[i].phase) << i;
  }
  EXPECT_EQ(a.best, b.best);
}

TEST(Tuner, StopsAtMaxEvaluationsAndNeverRepeatsAConfiguration) {
  TuneProblem p = bowlProblem();
  p.maxEvaluations = 7;
  int calls = 0;
  p.evaluate = [&](const std::vector<double>& v) { ++calls; return bowl(v); };
  TuneResult r = tune(p);
  EXPECT_EQ(calls, 7);
  EXPECT_EQ(r.evaluations.size(), 7u);
  // 7 evaluations leave room for a 1-point grid only (2x2 = 4 > 6/2): start, then the local search.
  EXPECT_EQ(r.gridPointsUsed, 1);
}

TEST(Tuner, IntegerDimensionsAreRoundedAndEvaluatedOnce) {
  TuneProblem p;
  p.dimensions = {{"n", 1, 9, true, false, 9}, {"x", 0, 1, false, false, 0.5}};
  std::vector<std::vector<double>> seen;
  p.evaluate = [&](const std::vector<double>& v) {
    seen.push_back(v);
    return TuneMeasure{std::abs(v[0] - 4) + (v[1] - 0.5) * (v[1] - 0.5), 0};
  };
  p.maxEvaluations = 40;
  TuneResult r = tune(p);
  for (const auto& v : seen) EXPECT_EQ(v[0], std::round(v[0]));
  std::sort(seen.begin(), seen.end());
  EXPECT_EQ(std::adjacent_find(seen.begin(), seen.end()), seen.end()) << "a configuration was evaluated twice";
  EXPECT_EQ(r.evaluations[size_t(r.best)].values[0], 4);
}

// A cheaper configuration is worse: the best one within the budget is on the budget's edge, and no
// configuration over it is ever called best.
TEST(Tuner, TheBudgetExcludesConfigurationsOverIt) {
  TuneProblem p;
  p.dimensions = {{"quality", 0, 10, false, false, 2}};
  p.evaluate = [](const std::vector<double>& v) { return TuneMeasure{10 - v[0], 1 + v[0]}; };  // cost 1..11 ms
  p.budget = 6.0;
  p.maxEvaluations = 30;
  TuneResult r = tune(p);
  ASSERT_GE(r.best, 0);
  const auto& best = r.evaluations[size_t(r.best)];
  EXPECT_LE(best.measure.cost, 6.0);
  EXPECT_GT(best.values[0], 4.5);  // near the edge at quality 5
  bool someOver = false;
  for (const auto& e : r.evaluations) {
    EXPECT_EQ(e.withinBudget, e.measure.cost <= 6.0);
    someOver |= !e.withinBudget;
  }
  EXPECT_TRUE(someOver) << "the grid should have tried something over the budget";
}

TEST(Tuner, NothingWithinTheBudgetHasNoBest) {
  TuneProblem p;
  p.dimensions = {{"q", 0, 1, false, false, 0.5}};
  p.evaluate = [](const std::vector<double>& v) { return TuneMeasure{v[0], 5}; };
  p.budget = 1.0;
  p.maxEvaluations = 5;
  EXPECT_EQ(tune(p).best, -1);
}

TEST(Tuner, AnObjectivesErrorReachesTheCaller) {
  TuneProblem p = bowlProblem();
  int calls = 0;
  p.evaluate = [&](const std::vector<double>& v) {
    if (++calls == 12) throw std::runtime_error("device lost");
    return bowl(v);
  };
  EXPECT_THROW(tune(p), std::runtime_error);
}

}  // namespace
}  // namespace aor

namespace aor {
namespace {

CrossValidationFold foldOf(const std::string& name, double before, double after) {
  CrossValidationFold f{name, {}};
  f.run.holdoutBefore.objective = before;
  f.run.holdoutAfter.objective = after;
  return f;
}

// The verdict of `tune --cv`: the fold that got worse by the most beyond the margin, else none.
TEST(CrossValidationVerdict, TheWorstFoldBeyondTheMarginIsRefusedAndNoneWithin) {
  std::vector<CrossValidationFold> folds{foldOf("a", 0.10, 0.09), foldOf("b", 0.10, 0.1019), foldOf("c", 0.20, 0.21),
                                         foldOf("d", 0.10, 0.108)};
  EXPECT_EQ(refusedFold(folds, 0.02), 3) << "d rose 8 %, c 5 %, b 1.9 % (within)";
  EXPECT_EQ(refusedFold(folds, 0.06), 3);
  EXPECT_EQ(refusedFold(folds, 0.09), -1) << "every rise within 9 %";
  EXPECT_EQ(refusedFold({foldOf("a", 0.1, 0.05)}, 0.0), -1);
  EXPECT_EQ(refusedFold({foldOf("a", 0.1, 0.1000001)}, 0.0), 0);
  EXPECT_EQ(refusedFold({foldOf("flat", 0.0, 0.0), foldOf("b", 0.1, 0.1)}, 0.02), -1) << "0 -> 0 is no change";
  EXPECT_EQ(foldOf("flat", 0.0, 0.0).change(), 0.0);
  EXPECT_EQ(refusedFold({foldOf("b", 0.1, 0.15), foldOf("flat", 0.0, 0.001)}, 0.02), 1) << "0 -> above 0 is the worst";
}

}  // namespace
}  // namespace aor
