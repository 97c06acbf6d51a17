// Temporal metrics on synthetic frames whose answers are known: a wall facing the camera (depth from
// the projection), outputs built as functions of pixel or world position, noise of known size.
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "metrics/temporal_metrics.h"
#include "metrics/temporal_reprojection.h"
#include "metrics/temporal_response.h"

namespace aor {
namespace {

constexpr int kWidth = 40, kHeight = 24;
constexpr size_t kPixels = size_t(kWidth) * size_t(kHeight);

glm::mat4 projection() {
  glm::mat4 p = glm::perspectiveRH_ZO(glm::radians(60.0f), float(kWidth) / float(kHeight), 0.1f, 100.0f);
  p[1][1] = -p[1][1];  // capture convention: Vulkan y points down
  return p;
}

// Depth-attachment value of a point `distance` in front of the camera.
float depthAt(float distance) {
  glm::mat4 p = projection();
  return (-p[2][2] * distance + p[3][2]) / distance;
}

glm::mat4 cameraAt(float x) { return glm::lookAtRH(glm::vec3(x, 0, 0), glm::vec3(x, 0, -1), glm::vec3(0, 1, 0)); }

// A wall at distance 10 everywhere, optionally a nearer block (distance 5) over columns [x0, x1).
std::vector<float> wallDepth(int blockX0 = 0, int blockX1 = 0) {
  std::vector<float> depth(kPixels, depthAt(10.0f));
  for (int y = 0; y < kHeight; ++y)
    for (int x = blockX0; x < blockX1; ++x) depth[size_t(y) * kWidth + size_t(x)] = depthAt(5.0f);
  return depth;
}

struct Frame {
  int index = 0;
  std::vector<float> depth = wallDepth();
  std::vector<float> visibility = std::vector<float>(kPixels, 0.5f);
  std::vector<float> reference;
  glm::mat4 view = cameraAt(0.0f);
  bool cut = false;
  bool historyValid = true;
  std::string resetReason;
  float historyWeight = 0.6f;
  AnalyzedFrame analyzed() const {
    AnalyzedFrame a{index, kWidth, kHeight, visibility.data(), depth.data(), view, projection(), cut, historyValid,
                    resetReason, reference.empty() ? nullptr : &reference};
    a.historyWeight = historyWeight;
    return a;
  }
};

Frame firstFrame() {
  Frame f;
  f.historyValid = false;
  f.resetReason = "first frame";
  return f;
}

TEST(TemporalReprojection, StillCameraMapsEveryPixelOntoItself) {
  auto depth = wallDepth(10, 20);
  auto g = frameGeometry(kWidth, kHeight, depth.data(), cameraAt(0), projection());
  EXPECT_NEAR(g.distance[0], 10.0f, 1e-3f);
  EXPECT_NEAR(g.distance[15], 5.0f, 1e-3f);
  auto r = reproject(g, g);
  EXPECT_EQ(r.count(PixelHistory::Reprojected), kPixels);
  for (size_t i = 0; i < kPixels; ++i) {
    EXPECT_NEAR(r.position[i].x, float(i % kWidth), 1e-3f);
    EXPECT_NEAR(r.position[i].y, float(i / kWidth), 1e-3f);
  }
}

TEST(TemporalReprojection, SidewaysMoveShiftsByTheProjectedDistanceAndRevealsWhatWasHidden) {
  // Previous frame: a near block over columns 10..19 hides the wall. The camera then moves 0.5 to
  // the right and the block is gone (e.g. it moved away): its pixels show the wall, which the
  // previous frame did not see there -> disoccluded by the depth test.
  auto prevDepth = wallDepth(10, 20), curDepth = wallDepth();
  auto previous = frameGeometry(kWidth, kHeight, prevDepth.data(), cameraAt(0.0f), projection());
  auto current = frameGeometry(kWidth, kHeight, curDepth.data(), cameraAt(0.5f), projection());
  auto r = reproject(current, previous);
  // A point at distance 10 moves by 0.5 * P00 * W/2 / 10 pixels, to the right in the previous frame.
  float shift = 0.5f * projection()[0][0] * kWidth * 0.5f / 10.0f;
  size_t disoccluded = 0, offscreen = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      size_t i = size_t(y) * kWidth + size_t(x);
      float previousX = float(x) + shift;
      bool offScreen = previousX > float(kWidth) - 0.5f;
      bool hidden = !offScreen && std::lround(previousX) >= 10 && std::lround(previousX) < 20;
      auto expected = (offScreen || hidden) ? PixelHistory::Disoccluded : PixelHistory::Reprojected;
      ASSERT_EQ(r.state[i], expected) << x << "," << y;
      if (expected == PixelHistory::Reprojected) {
        EXPECT_NEAR(r.position[i].x, previousX, 1e-3f);
      }
      disoccluded += hidden;
      offscreen += offScreen;
    }
  EXPECT_EQ(disoccluded, size_t(10 * kHeight));
  EXPECT_GT(offscreen, 0u);
}

TEST(TemporalReprojection, BilinearReadIsExactAtCentresAndLinearBetween) {
  std::vector<float> image(kPixels);
  for (size_t i = 0; i < kPixels; ++i) image[i] = float(i % kWidth) + 100.0f * float(i / kWidth);
  EXPECT_FLOAT_EQ(sampleBilinear(image, kWidth, kHeight, {3, 2}), 203.0f);
  EXPECT_FLOAT_EQ(sampleBilinear(image, kWidth, kHeight, {3.25f, 2.5f}), 253.25f);
  EXPECT_FLOAT_EQ(sampleBilinear(image, kWidth, kHeight, {-3.0f, 0.0f}), 0.0f);  // clamped to the edge
}

TEST(TemporalMetrics, StaticNoiseIsThePerPixelStandardDeviationOverTheStillFrames) {
  TemporalAnalysis analysis;
  for (int t = 0; t < 6; ++t) {
    Frame f = t == 0 ? firstFrame() : Frame{};
    f.index = t;
    // Pixel i alternates around 0.5 with amplitude a_i: population std-dev exactly a_i.
    for (size_t i = 0; i < kPixels; ++i) f.visibility[i] = 0.5f + (t % 2 ? 1.0f : -1.0f) * (i < kPixels / 2 ? 0.01f : 0.03f);
    analysis.addFrame(f.analyzed());
  }
  auto noise = analysis.staticNoise();
  EXPECT_EQ(noise.pixels, kPixels);
  EXPECT_NEAR(noise.mean, 0.02, 1e-6);
  EXPECT_NEAR(noise.p99, 0.03, 1e-6);
  auto summary = analysis.summaryJson();
  EXPECT_EQ(summary["static_noise"]["windows"], nlohmann::json::parse("[[0, 5]]"));
}

TEST(TemporalMetrics, NoStaticWindowWhenTheCameraMovesEveryFrame) {
  TemporalAnalysis analysis;
  for (int t = 0; t < 5; ++t) {
    Frame f = t == 0 ? firstFrame() : Frame{};
    f.index = t;
    f.view = cameraAt(0.1f * float(t));
    analysis.addFrame(f.analyzed());
  }
  EXPECT_EQ(analysis.staticNoise().pixels, 0u);
  EXPECT_TRUE(analysis.summaryJson()["static_noise"].is_null());
}

// Output that is a function of the world position of the wall: reprojection must make it match,
// while a per-pixel comparison would see the whole pattern shift.
float worldPattern(float worldX) { return 0.5f + 0.4f * std::sin(0.5f * worldX); }

Frame movingWallFrame(int t) {
  Frame f = t == 0 ? firstFrame() : Frame{};
  f.index = t;
  float cameraX = 0.2f * float(t);
  f.view = cameraAt(cameraX);
  float viewXPerPixel = 10.0f * 2.0f / (projection()[0][0] * kWidth);  // at distance 10
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      float ndcX = (2.0f * float(x) + 1.0f) / kWidth - 1.0f;
      f.visibility[size_t(y) * kWidth + size_t(x)] = worldPattern(cameraX + ndcX * viewXPerPixel * kWidth * 0.5f);
    }
  return f;
}

TEST(TemporalMetrics, WarpingErrorFollowsTheSurfaceNotThePixel) {
  TemporalAnalysis analysis;
  for (int t = 0; t < 3; ++t) analysis.addFrame(movingWallFrame(t).analyzed());
  auto frame1 = analysis.frameJson(1);
  ASSERT_TRUE(frame1.contains("warping_error"));
  // Only the bilinear interpolation error of a smooth pattern remains (~1e-5); a per-pixel
  // difference of the same frames (0.42 px shift) is ~1e-3.
  EXPECT_LT(frame1["warping_error"].get<double>(), 2e-5);
  EXPECT_FALSE(analysis.frameJson(0).contains("warping_error"));  // nothing before the first frame

  // A uniform brightening by 0.1 is flicker: warping error 0.01 exactly.
  TemporalAnalysis flicker;
  for (int t = 0; t < 2; ++t) {
    Frame f = t == 0 ? firstFrame() : Frame{};
    f.index = t;
    std::fill(f.visibility.begin(), f.visibility.end(), 0.5f + 0.1f * float(t));
    flicker.addFrame(f.analyzed());
  }
  EXPECT_NEAR(flicker.frameJson(1)["warping_error"].get<double>(), 0.01, 1e-6);
}

TEST(TemporalMetrics, WarpingErrorIsNotMeasuredAcrossACut) {
  TemporalAnalysis analysis;
  Frame a = firstFrame();
  Frame b;
  b.index = 1;
  b.cut = true;
  b.historyValid = false;
  b.resetReason = "cut";
  std::fill(b.visibility.begin(), b.visibility.end(), 0.9f);
  analysis.addFrame(a.analyzed());
  analysis.addFrame(b.analyzed());
  EXPECT_FALSE(analysis.frameJson(1).is_object() && analysis.frameJson(1).contains("warping_error"));
}

TEST(TemporalMetrics, DerivativeErrorIgnoresRealChangesAndCountsFlicker) {
  TemporalAnalysis analysis;
  for (int t = 0; t < 3; ++t) {
    Frame f = t == 0 ? firstFrame() : Frame{};
    f.index = t;
    f.reference.assign(kPixels, 0.3f + 0.2f * float(t));  // the true AO changes
    for (size_t i = 0; i < kPixels; ++i) f.visibility[i] = f.reference[i] + 0.05f;  // constant bias
    if (t == 2)
      for (size_t i = 0; i < kPixels; i += 2) f.visibility[i] += 0.1f;  // half the pixels flicker
    analysis.addFrame(f.analyzed());
  }
  EXPECT_NEAR(analysis.frameJson(1)["derivative_error"].get<double>(), 0.0, 1e-6);
  EXPECT_NEAR(analysis.frameJson(2)["derivative_error"].get<double>(), 0.05, 1e-6);
  EXPECT_NEAR(analysis.frameJson(1)["abs_error"].get<double>(), 0.05, 1e-6);
  EXPECT_EQ(analysis.summaryJson()["error_source"], "reference");
}

// The near block of the first frames moves away at frame 1: its pixels are disoccluded. The output
// there carries a ghost that decays as w^n with the frames since then; elsewhere it is exact.
TEST(TemporalMetrics, DisocclusionCurveFollowsRevealedPixelsAndGivesTheEmaResponse) {
  const float w = 0.6f, ghost = 0.4f, settledError = 0.02f;
  TemporalAnalysis analysis;
  std::vector<int> disoccludedAt(kPixels, -1);
  for (int t = 0; t < 16; ++t) {
    Frame f = t == 0 ? firstFrame() : Frame{};
    f.index = t;
    f.historyWeight = w;
    f.depth = t == 0 ? wallDepth(10, 20) : wallDepth();
    f.reference.assign(kPixels, 0.7f);
    for (size_t i = 0; i < kPixels; ++i) {
      int x = int(i % kWidth);
      bool revealed = t >= 1 && x >= 10 && x < 20;
      float error = revealed ? settledError + ghost * std::pow(w, float(t - 1)) : settledError;
      f.visibility[i] = f.reference[i] - error;
    }
    analysis.addFrame(f.analyzed());
  }
  EXPECT_NEAR(analysis.frameJson(1)["disoccluded_fraction"].get<double>(), 10.0 / kWidth, 1e-9);
  EXPECT_NEAR(analysis.frameJson(2)["disoccluded_fraction"].get<double>(), 0.0, 1e-9);
  auto curve = analysis.disocclusionCurve();
  ASSERT_EQ(curve.size(), 15u);  // ages 0..14 of the pixels revealed at frame 1
  for (size_t a = 0; a < curve.size(); ++a)
    EXPECT_NEAR(curve[a], settledError + ghost * std::pow(w, float(a)), 1e-5) << a;
  auto d = analysis.summaryJson()["disocclusion"];
  // ghost * 0.6^n <= 10% of ~0.02 (the tail mean, which still holds ~1e-4 of ghost): n = 10.
  EXPECT_EQ(d["response_frames"].get<int>(), 10);
  EXPECT_TRUE(d["settled"].get<bool>());
  EXPECT_GT(d["ghost_energy"].get<double>(), 0.9 * ghost / (1 - w));
  EXPECT_EQ(analysis.summaryJson()["ema"]["predicted_response_frames"], emaResponseFrames(w));
}

// Revealed pixels with different (constant) errors, half of them covered again later: a plain
// mean by age would change as that half drops out (0.2 -> 0.15); the paired curve stays flat.
TEST(TemporalMetrics, DisocclusionCurveDoesNotChangeWhenPixelsDropOut) {
  TemporalAnalysis analysis;
  for (int t = 0; t < 8; ++t) {
    Frame f = t == 0 ? firstFrame() : Frame{};
    f.index = t;
    f.depth = t == 0 ? wallDepth(10, 20) : t >= 3 ? wallDepth(15, 20) : wallDepth();
    f.reference.assign(kPixels, 0.7f);
    for (size_t i = 0; i < kPixels; ++i) {
      int x = int(i % kWidth);
      float error = x < 10 || x >= 20 ? 0.0f : x < 15 ? 0.1f : t < 3 ? 0.3f : 0.2f;
      f.visibility[i] = f.reference[i] - error;
    }
    analysis.addFrame(f.analyzed());
  }
  auto curve = analysis.disocclusionCurve();
  ASSERT_GE(curve.size(), 5u);
  for (size_t a = 0; a < curve.size(); ++a) EXPECT_NEAR(curve[a], 0.2, 1e-6) << a;
}

TEST(TemporalMetrics, EveryResetStartsACurveUntilTheNextReset) {
  TemporalAnalysis analysis;
  for (int t = 0; t < 8; ++t) {
    Frame f = t == 0 ? firstFrame() : Frame{};
    f.index = t;
    if (t == 4) {
      f.cut = true;
      f.historyValid = false;
      f.resetReason = "cut";
      f.view = cameraAt(30.0f);
    }
    if (t > 4) f.view = cameraAt(30.0f);
    int since = t < 4 ? t : t - 4;
    f.reference.assign(kPixels, 0.5f);
    std::fill(f.visibility.begin(), f.visibility.end(), 0.5f + 0.2f * std::pow(0.5f, float(since)));
    analysis.addFrame(f.analyzed());
  }
  auto summary = analysis.summaryJson();
  ASSERT_EQ(summary["resets"].size(), 2u);
  EXPECT_EQ(summary["resets"][1]["frame"], 4);
  EXPECT_EQ(summary["resets"][1]["reason"], "cut");
  EXPECT_EQ(summary["resets"][1]["abs_error"].size(), 4u);
  EXPECT_EQ(analysis.frameJson(4)["response_frames"], summary["resets"][1]["response_frames"]);
  EXPECT_FALSE(analysis.frameJson(5).contains("response_frames"));
}

}  // namespace
}  // namespace aor
