// Reference AO against closed-form oracles, and the sampling building blocks.
#include <cmath>
#include <set>

#include <gtest/gtest.h>

#include "generator/generator_internal.h"

using namespace aor::gen;
using glm::dvec3;

namespace {

const RayScene& pitScene() {
  static const RayScene scene("pit");
  return scene;
}
const RayScene& sphereScene() {
  static const RayScene scene("sphere");
  return scene;
}
const RayScene& planeScene() {
  static const RayScene scene("plane");
  return scene;
}

}  // namespace

TEST(Sampling, SobolFirstPointsAreTheKnownSequence) {
  EXPECT_EQ(sobol2(0), glm::dvec2(0.0, 0.0));
  EXPECT_EQ(sobol2(1), glm::dvec2(0.5, 0.5));
  EXPECT_EQ(sobol2(2), glm::dvec2(0.25, 0.75));
  EXPECT_EQ(sobol2(3), glm::dvec2(0.75, 0.25));
}

// The first 2^m points of a (0,2)-sequence form a (0,m,2)-net: every elementary interval of area
// 2^-m holds exactly one point, for every split of m into x and y resolution.
TEST(Sampling, SobolPrefixesAreZeroNets) {
  for (int m : {2, 5, 8, 10}) {
    const int n = 1 << m;
    for (int k = 0; k <= m; ++k) {
      std::set<std::pair<int, int>> cells;
      for (int i = 0; i < n; ++i) {
        const glm::dvec2 s = sobol2(static_cast<uint32_t>(i));
        ASSERT_GE(s.x, 0.0);
        ASSERT_LT(s.x, 1.0);
        cells.insert({static_cast<int>(s.x * (1 << k)), static_cast<int>(s.y * (1 << (m - k)))});
      }
      EXPECT_EQ(static_cast<int>(cells.size()), n) << "m=" << m << " k=" << k;
    }
  }
}

TEST(Sampling, PixelKeysDifferAndRepeat) {
  EXPECT_EQ(pixelSampleKey(3, 4, 5, 1), pixelSampleKey(3, 4, 5, 1));
  EXPECT_NE(pixelSampleKey(3, 4, 5, 1), pixelSampleKey(4, 3, 5, 1));
  EXPECT_NE(pixelSampleKey(3, 4, 5, 1), pixelSampleKey(3, 4, 6, 1));
  EXPECT_NE(pixelSampleKey(3, 4, 5, 1), pixelSampleKey(3, 4, 5, 2));
}

TEST(Oracle, PitBottomCentreDirect) {
  const double a = 1.0, H = 1.0;
  const double expected = a * a / (a * a + H * H);
  for (uint64_t key : {1ull, 0x1234567890abcdefull}) {
    const double v = referenceVisibility(pitScene(), {0.0, -1.0, 0.0}, {0.0, 1.0, 0.0}, 2.0, 4096, key, 1e-4);
    EXPECT_NEAR(v, expected, 0.01) << "key " << key;
  }
  // With a radius shorter than the rim distance the walls are partly out of reach: more open.
  const double shortR = referenceVisibility(pitScene(), {0.0, -1.0, 0.0}, {0.0, 1.0, 0.0}, 1.0, 1024, 7, 1e-4);
  EXPECT_GT(shortR, expected + 0.05);
}

TEST(Oracle, PitBottomCentreThroughThePixelLookingDownTheAxis) {
  // Odd image: pixel (2,2) of a 5x5 image is exactly the image centre, i.e. the pit axis.
  FrameCamera cam;
  cam.view = makeView({0.0, 4.0, 0.0}, {0.0, -1.0, 0.0}, {0.0, 0.0, -1.0});
  cam.projection = makeProjection(30.0, 1.0, false, false);
  RenderSettings rs;
  rs.width = 5;
  rs.height = 5;
  rs.referenceSpp = 4096;
  rs.radius = 2.0;
  const auto frame = renderFrame(pitScene(), cam, rs, 0);
  const size_t c = 2 * 5 + 2;
  const PixelRay ray = pixelRay(cam.view, cam.projection, false, 2, 2, 5, 5);
  EXPECT_NEAR(ray.direction.y, -1.0, 1e-9);
  // Depth of the bottom (5 m below the camera) and the upward normal.
  const double n = kNearPlane, f = kFarPlane, d = 5.0;
  EXPECT_NEAR(frame.gbuffer.depth[c], f / (f - n) * (1.0 - n / d), 1e-6);
  EXPECT_NEAR(frame.gbuffer.normals[3 * c + 1], 1.0f, 1e-6);
  ASSERT_TRUE(frame.reference.has_value());
  EXPECT_NEAR((*frame.reference)[c], 0.5, 0.01);
}

TEST(Oracle, SphereOnFloor) {
  const double r = 1.0;
  const double R = sphereScene().info().defaultRadius;
  EXPECT_GE(R, 50.0);
  for (double x : {0.25, 0.5, 1.0, 1.5, 2.0, 4.0}) {
    const double expected = 1.0 - r * r * r / std::pow(x * x + r * r, 1.5);
    const double v = referenceVisibility(sphereScene(), {x, 0.0, 0.0}, {0.0, 1.0, 0.0}, R, 4096,
                                         pixelSampleKey(static_cast<int>(x * 100), 0, 0, 1), 1e-4);
    EXPECT_NEAR(v, expected, 0.01) << "x=" << x;
  }
  // Same for a point in another direction around the contact point.
  const double v = referenceVisibility(sphereScene(), {0.0, 0.0, -1.0}, {0.0, 1.0, 0.0}, R, 4096, 99, 1e-4);
  EXPECT_NEAR(v, 1.0 - 1.0 / std::pow(2.0, 1.5), 0.01);
}

TEST(Oracle, SphereTopIsFullyOpen) {
  EXPECT_EQ(referenceVisibility(sphereScene(), {0.0, 2.0, 0.0}, {0.0, 1.0, 0.0}, 100.0, 256, 3, 1e-4), 1.0);
}

TEST(Oracle, PlaneIsOpenEverywhereEvenFromAGrazingCamera) {
  // Camera 1 m above the plane looking 5 degrees below the horizon.
  const double pitch = 5.0 * 3.14159265358979323846 / 180.0;
  const dvec3 eye(0.0, 1.0, 0.0);
  FrameCamera cam;
  cam.view = makeView(eye, eye + dvec3(0.0, -std::sin(pitch), -std::cos(pitch)));
  cam.projection = makeProjection(60.0, 64.0 / 36.0, false, false);
  RenderSettings rs;
  rs.width = 64;
  rs.height = 36;
  rs.referenceSpp = 32;
  rs.radius = 1.0;
  const auto frame = renderFrame(planeScene(), cam, rs, 0);
  ASSERT_TRUE(frame.reference.has_value());
  int hits = 0, sky = 0;
  for (size_t i = 0; i < frame.gbuffer.depth.size(); ++i) {
    EXPECT_GE((*frame.reference)[i], 0.99f) << "pixel " << i;
    (frame.gbuffer.depth[i] == 1.0f ? sky : hits)++;
  }
  EXPECT_GT(hits, 64 * 10);
  EXPECT_GT(sky, 64 * 5);
  // Grazing hits far away still leave the surface cleanly (epsilon scales with distance).
  EXPECT_EQ(referenceVisibility(planeScene(), {150.0, 0.0, -120.0}, {0.0, 1.0, 0.0}, 1.0, 512, 5,
                                surfaceEpsilon(190.0)),
            1.0);
}

TEST(Oracle, NearbyWallMatchesTheProjectedDiskArea) {
  // Cosine-weighted directions project to points uniform on the unit disk, so a flat wall at
  // distance d blocks (within radius R) exactly the disk segment beyond x = d/R:
  // visibility = 1 - (acos(k) - k sqrt(1 - k^2)) / pi with k = d/R. The pit wall (radius 1) is
  // flat enough at this scale; a uniform (not cosine) hemisphere would give a different value.
  const double d = 0.005, R = 0.01, k = d / R;
  const double expected = 1.0 - (std::acos(k) - k * std::sqrt(1.0 - k * k)) / 3.14159265358979323846;
  const double v = referenceVisibility(pitScene(), {1.0 - d, -1.0, 0.0}, {0.0, 1.0, 0.0}, R, 4096, 11, 1e-6);
  EXPECT_NEAR(v, expected, 0.01);
}
