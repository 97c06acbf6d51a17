// Response time, ghost energy and the EMA prediction on curves whose answers are known in closed form.
#include <cmath>

#include <gtest/gtest.h>

#include "metrics/temporal_response.h"

namespace aor {
namespace {

TEST(TemporalResponse, EmaPredictionIsTheFirstFrameWhoseResidualIsTenPercent) {
  EXPECT_EQ(emaResponseFrames(0.0), 0);
  EXPECT_EQ(emaResponseFrames(0.5), 4);   // 0.5^3 = 0.125, 0.5^4 = 0.0625
  EXPECT_EQ(emaResponseFrames(0.9), 22);  // 0.9^21 = 0.109, 0.9^22 = 0.098
  EXPECT_EQ(emaResponseFrames(0.98), 114);
  for (double w : {0.3, 0.6, 0.75, 0.9}) {
    int n = emaResponseFrames(w);
    EXPECT_LE(std::pow(w, n), 0.1) << w;
    EXPECT_GT(std::pow(w, n - 1), 0.1) << w;
  }
  auto residual = emaResidual(0.5, 4);
  ASSERT_EQ(residual.size(), 4u);
  EXPECT_DOUBLE_EQ(residual[0], 1.0);
  EXPECT_DOUBLE_EQ(residual[3], 0.125);
}

TEST(TemporalResponse, DecayingGhostOnTopOfASettledErrorGivesTheEmaResponse) {
  const double settled = 0.02, ghost = 0.3, w = 0.6;
  std::vector<double> curve;
  for (int n = 0; n < 30; ++n) curve.push_back(settled + ghost * std::pow(w, n));
  auto r = analyzeResponse(curve, w);
  // Tail mean: the ghost left in frames 27..29 is below 1e-6.
  EXPECT_NEAR(r.settled, settled, 1e-6);
  EXPECT_TRUE(r.settledReached);
  // First n with ghost * w^n <= 10% of settled: 0.3 * 0.6^n <= 0.002 -> n >= 9.8.
  EXPECT_EQ(r.responseFrames, 10);
  // The EMA's own prediction for this excess: ceil(ln(0.1 * 0.02 / 0.3) / ln 0.6) = 10.
  EXPECT_EQ(r.emaFrames, 10);
  // Sum of the excess: ghost * (1 - w^30) / (1 - w), less the tiny tail part counted in `settled`.
  EXPECT_NEAR(r.ghostEnergy, ghost / (1.0 - w), 1e-4);
}

TEST(TemporalResponse, FlatCurveRespondsAtOnceAndShortCurveIsNotSettled) {
  auto flat = analyzeResponse({0.05, 0.05, 0.05, 0.05}, 0.3);  // w = 0.3: EMA predicts 2 frames
  EXPECT_EQ(flat.responseFrames, 0);
  EXPECT_DOUBLE_EQ(flat.ghostEnergy, 0.0);
  EXPECT_FALSE(flat.settledReached);  // the tail starts at frame 1, before the predicted 2
  auto perfect = analyzeResponse({0.0, 0.0, 0.0}, 0.0);
  EXPECT_EQ(perfect.responseFrames, 0);
  auto empty = analyzeResponse({}, 0.5);
  EXPECT_EQ(empty.responseFrames, 0);
  // Rising towards the settled value (a no-history comparison right after a reset) counts too.
  auto rising = analyzeResponse({0.0, 0.05, 0.08, 0.1, 0.1, 0.1}, 0.1);
  EXPECT_NEAR(rising.settled, 0.1, 1e-12);
  EXPECT_EQ(rising.responseFrames, 3);
  EXPECT_DOUBLE_EQ(rising.ghostEnergy, 0.0);
}

}  // namespace
}  // namespace aor
