// The half-resolution upsample's weights (shaders/temporal_denoise.h), on the CPU: bilinear in the
// pixel's place between the texels, cut by depth edges, plain bilinear when no texel matches.
#include <gtest/gtest.h>

#include "blocks/temporal_denoise.h"

namespace aor::shader {
namespace {

float sum(vec4 w) { return w.x + w.y + w.z + w.w; }

TEST(UpsampleWeights, AnEvaluatedPixelTakesItsOwnTexelAlone) {
  // Pixel 2t: fraction 0, whatever the other texels hold (another surface, sky).
  vec4 w = upsampleWeights(vec2(0.0f), 10.0f, vec4(10.0f, 30.0f, -1.0f, 10.5f));
  EXPECT_EQ(w, vec4(1.0f, 0.0f, 0.0f, 0.0f));
}

TEST(UpsampleWeights, OnOneSurfaceTheyAreBilinear) {
  vec4 between = upsampleWeights(vec2(0.5f, 0.0f), 10.0f, vec4(10.0f));
  EXPECT_EQ(between, vec4(0.5f, 0.5f, 0.0f, 0.0f));
  vec4 centre = upsampleWeights(vec2(0.5f, 0.5f), 10.0f, vec4(10.0f));
  EXPECT_EQ(centre, vec4(0.25f));
}

TEST(UpsampleWeights, ATexelAcrossADepthEdgeGetsNothing) {
  // Texels 1 and 3 lie on a surface 50 % farther: the pixel blends only texels 0 and 2.
  vec4 w = upsampleWeights(vec2(0.5f, 0.5f), 10.0f, vec4(10.0f, 15.0f, 10.0f, 15.0f));
  EXPECT_EQ(w.y, 0.0f);
  EXPECT_EQ(w.w, 0.0f);
  EXPECT_EQ(w.x, 0.25f);
  EXPECT_EQ(w.z, 0.25f);
  // Within the spatial pass's 5 % tolerance the weight falls off linearly, not at once.
  vec4 near = upsampleWeights(vec2(0.5f, 0.0f), 10.0f, vec4(10.0f, 10.25f, 10.0f, 10.0f));
  EXPECT_GT(near.y, 0.0f);
  EXPECT_LT(near.y, near.x);
}

TEST(UpsampleWeights, SkyMatchesOnlySky) {
  vec4 w = upsampleWeights(vec2(0.5f, 0.0f), kSkyDistance, vec4(kSkyDistance, 12.0f, 0.0f, 0.0f));
  EXPECT_EQ(w, vec4(0.5f, 0.0f, 0.0f, 0.0f));
}

TEST(UpsampleWeights, NoMatchingTexelFallsBackToBilinear) {
  // A thin feature seen only at odd pixels: no texel is on its surface.
  vec4 w = upsampleWeights(vec2(0.5f, 0.5f), 3.0f, vec4(10.0f, 11.0f, 12.0f, kSkyDistance));
  EXPECT_EQ(w, vec4(0.25f));
  EXPECT_EQ(sum(w), 1.0f);
}

}  // namespace
}  // namespace aor::shader
