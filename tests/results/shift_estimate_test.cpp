// The Hodges-Lehmann shift, its interval, and U's exact null distribution, against values worked
// out by hand.
#include <gtest/gtest.h>

#include "results/shift_estimate.h"

namespace aor::results {
namespace {

TEST(MannWhitneyNullCdf, SmallSizesMatchTheCountedArrangements) {
  // m = n = 2: the 6 arrangements have U = 0, 1, 2, 2, 3, 4.
  auto cdf = mannWhitneyNullCdf(2, 2);
  ASSERT_EQ(cdf.size(), 5u);
  EXPECT_DOUBLE_EQ(cdf[0], 1.0 / 6);
  EXPECT_DOUBLE_EQ(cdf[1], 2.0 / 6);
  EXPECT_DOUBLE_EQ(cdf[2], 4.0 / 6);
  EXPECT_DOUBLE_EQ(cdf[4], 1.0);
  // m = n = 5: U = 0, 1 one way each, U = 2 two ways, of C(10, 5) = 252.
  auto five = mannWhitneyNullCdf(5, 5);
  EXPECT_DOUBLE_EQ(five[2], 4.0 / 252);
  EXPECT_DOUBLE_EQ(five[25], 1.0);
  // Symmetric: P(U <= u) = P(U >= mn - u).
  auto uneven = mannWhitneyNullCdf(3, 7);
  for (size_t u = 0; u + 1 < uneven.size(); ++u) EXPECT_NEAR(uneven[u], 1 - uneven[21 - u - 1], 1e-12) << u;
}

TEST(HodgesLehmann, ShiftIsTheMedianOfTheDifferences) {
  auto e = hodgesLehmann({1, 2, 3, 4}, {11, 12, 13, 14}, 0.95);
  EXPECT_DOUBLE_EQ(e.shift, 10);
  // 4 a side: P(U = 0) = 1/70 <= 0.025 < P(U <= 1) = 2/70, so c = 1: the extreme differences.
  EXPECT_DOUBLE_EQ(e.lower, 7);
  EXPECT_DOUBLE_EQ(e.upper, 13);
  EXPECT_NEAR(e.confidence, 1 - 2.0 / 70, 1e-12);
}

TEST(HodgesLehmann, IntervalNarrowsWithMoreValues) {
  std::vector<double> before, after;
  for (int i = 0; i < 10; ++i) before.push_back(i), after.push_back(i + 5);
  auto e = hodgesLehmann(before, after, 0.95);
  EXPECT_DOUBLE_EQ(e.shift, 5);
  // 10 a side: c = 24 (P(U <= 23) = 0.0216, P(U <= 24) = 0.0262), so D(24) and D(77) of 100.
  EXPECT_DOUBLE_EQ(e.lower, 2);
  EXPECT_DOUBLE_EQ(e.upper, 8);
  EXPECT_GE(e.confidence, 0.95);
}

TEST(HodgesLehmann, TooFewValuesSayWhatTheyCover) {
  auto e = hodgesLehmann({1, 2}, {3, 4}, 0.95);  // P(U = 0) = 1/6 > 0.025
  EXPECT_DOUBLE_EQ(e.lower, 1);
  EXPECT_DOUBLE_EQ(e.upper, 3);
  EXPECT_NEAR(e.confidence, 1 - 2.0 / 6, 1e-12);
}

}  // namespace
}  // namespace aor::results
