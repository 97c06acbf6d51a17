// SAO's per-tap math (shaders/sao/sao.h), checked on the CPU: the rotated grid keeps one texel of
// every 2x2 block at alternating offsets, taps pick the level their distance asks for, the
// estimator ignores what lies in the tangent plane or beyond the radius, the blur's weights fall
// with distance and depth, and the presets' spiral turns never line taps up.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>

#include <gtest/gtest.h>

#include "sao/sao.h"
#include "techniques/sao/sao_settings.h"

namespace aor::shader {
namespace {

TEST(SaoMath, RotatedGridKeepsOneTexelOfEachBlockAtAlternatingOffsets) {
  const ivec2 source(64, 64);
  std::set<std::pair<int, int>> offsets;
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) {
      ivec2 s = saoRotatedGridSource(ivec2(x, y), source);
      EXPECT_EQ(s.x / 2, x) << "inside its own 2x2 block";
      EXPECT_EQ(s.y / 2, y);
      offsets.insert({s.x % 2, s.y % 2});
    }
  EXPECT_EQ(offsets.size(), 4u) << "each of the four texels of a block is kept by one of four neighbours";
  EXPECT_EQ(saoRotatedGridSource(ivec2(0, 0), source), ivec2(1, 1));
  // An odd last column or row keeps a real texel: clamped into the level above.
  EXPECT_EQ(saoRotatedGridSource(ivec2(2, 2), ivec2(5, 5)), ivec2(4, 4));
}

TEST(SaoMath, TapsReadTheLevelTheirDistanceSelects) {
  EXPECT_EQ(saoMipLevel(0.4f, 4), 0);
  EXPECT_EQ(saoMipLevel(15.9f, 4), 0);   // up to 2^(3+1) pixels: level 0
  EXPECT_EQ(saoMipLevel(16.0f, 4), 1);
  EXPECT_EQ(saoMipLevel(32.0f, 4), 2);
  EXPECT_EQ(saoMipLevel(64.0f, 4), 3);
  EXPECT_EQ(saoMipLevel(128.0f, 4), 4);
  EXPECT_EQ(saoMipLevel(4096.0f, 4), 4);  // clamped to the pyramid
  EXPECT_EQ(saoMipLevel(4096.0f, 2), 2);  // a small frame's shorter pyramid
}

TEST(SaoMath, TheSpiralGoesOutwardAndTurnsTauTimes) {
  float previous = 0.0f, angleTurned = 0.0f;
  vec2 last(1.0f, 0.0f);
  for (int i = 0; i < 19; ++i) {
    float r;
    vec2 d = saoTapLocation(i, 19, 7.0f, 0.0f, r);
    EXPECT_NEAR(length(d), 1.0f, 1e-6f);
    EXPECT_GT(r, previous);
    EXPECT_LT(r, 1.0f);
    previous = r;
    if (i > 0) angleTurned += std::acos(std::clamp(dot(d, last), -1.0f, 1.0f));
    last = d;
  }
  // 18 steps of 7/19 of a turn each, measured as the short way round.
  float step = 7.0f / 19.0f * 2.0f * kPi;
  EXPECT_NEAR(angleTurned, 18.0f * std::min(step, 2.0f * kPi - step), 1e-3f);
}

TEST(SaoMath, TheEstimatorIgnoresTheTangentPlaneAndWhatLiesBeyondTheRadius) {
  const vec3 n(0, 0, 1);
  const float invR2 = 1.0f, bias = 0.023f;
  EXPECT_EQ(saoTapObscurance(vec3(0.5f, 0, 0), n, invR2, bias), 0.0f);       // in the plane
  EXPECT_EQ(saoTapObscurance(vec3(0.5f, 0, 0.02f), n, invR2, bias), 0.0f);   // within the bias
  EXPECT_EQ(saoTapObscurance(vec3(0.5f, 0, -0.3f), n, invR2, bias), 0.0f);   // below the surface
  EXPECT_EQ(saoTapObscurance(vec3(0.9f, 0, 0.5f), n, invR2, bias), 0.0f);    // beyond r = 1
  float near = saoTapObscurance(vec3(0.1f, 0, 0.3f), n, invR2, bias);
  float far = saoTapObscurance(vec3(0.3f, 0, 0.6f), n, invR2, bias);
  EXPECT_GT(near, far);
  EXPECT_GT(far, 0.0f);
  // At the radius range's end no power of r is formed: finite, and still an occluder.
  float huge = saoTapObscurance(vec3(1e6f, 0, 3e6f), n, 1.0f / (1e7f * 1e7f), bias);
  EXPECT_TRUE(std::isfinite(huge));
  EXPECT_GT(huge, 0.0f);
  EXPECT_EQ(saoVisibility(0.0f, 1.0f), 1.0f);
  EXPECT_EQ(saoVisibility(10.0f, 1.0f), 0.0f);
}

TEST(SaoMath, BlurWeightsFallWithDistanceAndDepth) {
  EXPECT_EQ(saoBlurWeight(0, 2.0f, 0.0f, 1.0f), 1.0f);
  EXPECT_LT(saoBlurWeight(2, 2.0f, 0.0f, 1.0f), saoBlurWeight(1, 2.0f, 0.0f, 1.0f));
  EXPECT_LT(saoBlurWeight(1, 2.0f, 0.05f, 1.0f), saoBlurWeight(1, 2.0f, 0.0f, 1.0f));
  EXPECT_EQ(saoBlurWeight(1, 2.0f, 1.0f / kSaoEdgeScale, 1.0f), 0.0f);
  EXPECT_EQ(saoBlurWeight(1, 2.0f, 5.0f, 0.0f), saoBlurWeight(1, 2.0f, 0.0f, 0.0f)) << "sharpness 0: plain Gaussian";
}

TEST(SaoMath, ThePresetsSpiralTurnsShareNoFactorWithTheirTapCount) {
  for (int samples : {9, 13, 19, 31}) EXPECT_EQ(std::gcd(samples, aor::saoSpiralTurnsFor(samples)), 1) << samples;
  EXPECT_EQ(aor::saoSpiralTurnsFor(19), 7);
}

}  // namespace
}  // namespace aor::shader
