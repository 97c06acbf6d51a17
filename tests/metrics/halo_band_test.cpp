// The halo band: the background within its projected AO radius of a nearer silhouette, and nothing
// else (not the occluder, not a smooth surface, not sky).
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "metrics/halo_band.h"

namespace aor {
namespace {

constexpr int kW = 40, kH = 20;

// A wall at distance 10 with a 4x4 plate at distance 5 in front of it, at x, y in [10, 14).
std::vector<float> plateBeforeWall() {
  std::vector<float> d(kW * kH, 10.0f);
  for (int y = 10; y < 14; ++y)
    for (int x = 10; x < 14; ++x) d[y * kW + x] = 5.0f;
  return d;
}

HaloBandOptions reachOf(int pixelsAtTheWall) {
  HaloBandOptions o;
  o.radius = 1.0f;
  o.pixelsPerUnit = float(pixelsAtTheWall) * 10.0f;  // pixelsPerUnit * radius / 10
  return o;
}

TEST(HaloBand, IsTheBackgroundWithinItsReachOfTheSilhouette) {
  auto band = haloBandMask(plateBeforeWall(), kW, kH, reachOf(3));
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      bool plate = x >= 10 && x < 14 && y >= 10 && y < 14;
      // Chebyshev distance to the plate's pixels (all of them are silhouette pixels).
      int dx = x < 10 ? 10 - x : (x > 13 ? x - 13 : 0), dy = y < 10 ? 10 - y : (y > 13 ? y - 13 : 0);
      bool expected = !plate && std::max(dx, dy) <= 3;
      EXPECT_EQ(bool(band[y * kW + x]), expected) << x << "," << y;
    }
}

TEST(HaloBand, SmoothSurfacesAndSkyHaveNone) {
  std::vector<float> ramp(kW * kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) ramp[y * kW + x] = 5.0f * (1.0f + 0.05f * float(y));  // 5 % a row: no silhouette
  for (uint8_t b : haloBandMask(ramp, kW, kH, reachOf(5))) EXPECT_EQ(b, 0);
  // Sky beside a surface: the surface's edge is a silhouette, but sky is never in the band.
  std::vector<float> half(kW * kH, -1.0f);
  for (int i = 0; i < kW * kH / 2; ++i) half[i] = 8.0f;
  for (uint8_t b : haloBandMask(half, kW, kH, reachOf(5))) EXPECT_EQ(b, 0);
}

TEST(HaloBand, MaskedErrorPoolsOnlyTheFlaggedPixels) {
  std::vector<float> out{0.5f, 0.9f, 0.2f}, ref{0.4f, 0.1f, 0.4f};
  auto e = maskedError(out.data(), ref.data(), {1, 0, 1});
  EXPECT_EQ(e.pixels, 2);
  EXPECT_NEAR(e.rmse, std::sqrt((0.01 + 0.04) / 2.0), 1e-6);
  EXPECT_NEAR(e.bias, (0.1 - 0.2) / 2.0, 1e-6);
}

}  // namespace
}  // namespace aor
