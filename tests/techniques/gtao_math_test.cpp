// The shader's closed forms, checked on the CPU: the identity-expanded integrals the GTAO pass
// evaluates equal the paper's direct forms, and an unoccluded slice averages to exactly 1.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "gtao/gtao.h"

namespace aor::shader {
namespace {

struct SliceAngles {
  float n, hNeg, hPos;
};

std::vector<SliceAngles> randomSlices() {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<SliceAngles> slices;
  for (int i = 0; i < 2000; ++i) {
    float n = (unit(rng) * 2.0f - 1.0f) * kHalfPi;
    slices.push_back({n, n - unit(rng) * kHalfPi, n + unit(rng) * kHalfPi});  // hNeg <= n <= hPos
  }
  return slices;
}

TEST(GtaoMath, ExpandedVisibilityEqualsTheDirectIntegral) {
  for (auto s : randomSlices()) {
    float direct = gtaoSliceVisibility(s.hPos, -s.hNeg, s.n);
    float expanded = gtaoHorizonVisibility(s.hPos, std::cos(s.hPos), std::sin(s.hPos), std::cos(s.n), std::sin(s.n)) +
                     gtaoHorizonVisibility(s.hNeg, std::cos(s.hNeg), std::sin(s.hNeg), std::cos(s.n), std::sin(s.n));
    EXPECT_NEAR(expanded, direct, 2e-6f) << "n " << s.n << " h " << s.hNeg << " " << s.hPos;
  }
}

TEST(GtaoMath, ExpandedBentNormalEqualsAlgorithmTwo) {
  for (auto s : randomSlices()) {
    vec2 direct = gtaoSliceBentNormal(s.hNeg, s.hPos, s.n);
    float cosN = std::cos(s.n), sinN = std::sin(s.n);
    vec2 terms = gtaoHorizonBentTerms(std::cos(s.hNeg), std::sin(s.hNeg), cosN, sinN) +
                 gtaoHorizonBentTerms(std::cos(s.hPos), std::sin(s.hPos), cosN, sinN);
    vec2 expanded((terms.x + 16.0f * sinN) / 12.0f, (terms.y + 8.0f * cosN) / 12.0f);
    EXPECT_NEAR(expanded.x, direct.x, 5e-6f);
    EXPECT_NEAR(expanded.y, direct.y, 5e-6f);
  }
}

TEST(GtaoMath, UnoccludedSliceIsTheTangentPlaneIntegralAndAveragesToOne) {
  for (float tilt : {0.0f, 0.3f, 1.0f, 1.4f}) {  // normal tilted from the view vector
    double sum = 0;
    const int slices = 4096;
    for (int i = 0; i < slices; ++i) {
      float phi = (float(i) + 0.5f) * kPi / float(slices);
      float n = std::atan(std::tan(tilt) * std::cos(phi));
      float projectedLength = std::sqrt(std::pow(std::sin(tilt) * std::cos(phi), 2.0f) + std::pow(std::cos(tilt), 2.0f));
      float unoccluded = gtaoUnoccludedSlice(n, std::cos(n), std::sin(n));
      EXPECT_NEAR(unoccluded, gtaoSliceVisibility(n + kHalfPi, kHalfPi - n, n), 1e-5f);
      sum += projectedLength * unoccluded;
    }
    EXPECT_NEAR(sum / slices, 1.0, 1e-5) << "tilt " << tilt;
  }
}

}  // namespace
}  // namespace aor::shader
