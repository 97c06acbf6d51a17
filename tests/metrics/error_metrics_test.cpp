// Error metrics against a reference: values checked against hand-computed cases.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "metrics/error_metrics.h"

using namespace aor;

namespace {

glm::mat4 standardProjection() {
  glm::mat4 p(0.0f);
  p[2][2] = -1.0f;
  p[3][2] = -0.05f;  // standard infinite: near maps to 0, far to 1
  p[2][3] = -1.0f;
  return p;
}

glm::mat4 reversedProjection() {
  glm::mat4 p = standardProjection();
  p[2][2] = 0.0f;
  p[3][2] = 0.05f;
  return p;
}

struct Images {
  int width, height;
  std::vector<float> output, reference, depth;
};

Images constantImages(int width, int height, float output, float reference, float depth) {
  size_t n = size_t(width) * size_t(height);
  return {width, height, std::vector<float>(n, output), std::vector<float>(n, reference), std::vector<float>(n, depth)};
}

AnalyzedFrame frameOf(const Images& images, int index, const std::vector<float>& reference, const glm::mat4& projection) {
  AnalyzedFrame f;
  f.index = index;
  f.width = images.width;
  f.height = images.height;
  f.visibility = images.output.data();
  f.depth = images.depth.data();
  f.projection = projection;
  f.reference = &reference;
  return f;
}

}  // namespace

TEST(ErrorMetrics, IdenticalImagesHaveNoError) {
  auto im = constantImages(16, 12, 0.5f, 0.5f, 0.3f);
  for (size_t i = 0; i < im.output.size(); ++i) im.output[i] = im.reference[i] = float(i % 7) / 7.0f;
  auto m = computeErrorMetrics(im.output.data(), im.reference.data(), im.depth.data(), 16, 12, false);
  EXPECT_EQ(m.pixels, 16 * 12);
  EXPECT_EQ(m.rmse, 0.0);
  EXPECT_EQ(m.maxError, 0.0);
  EXPECT_EQ(m.p99, 0.0);
  EXPECT_NEAR(m.ssim, 1.0, 1e-12);
  EXPECT_TRUE(std::isinf(m.psnr));
  EXPECT_TRUE(toJson(m)["psnr"].is_null());
}

TEST(ErrorMetrics, ConstantOffsetGivesKnownValues) {
  auto im = constantImages(10, 10, 0.6f, 0.5f, 0.3f);
  auto m = computeErrorMetrics(im.output.data(), im.reference.data(), im.depth.data(), 10, 10, false);
  const double e = double(0.6f) - double(0.5f);
  EXPECT_NEAR(m.rmse, e, 1e-12);
  EXPECT_NEAR(m.mae, e, 1e-12);
  EXPECT_NEAR(m.maxError, e, 1e-12);
  EXPECT_NEAR(m.bias, e, 1e-12);
  EXPECT_NEAR(m.p99, e, 1e-12);
  EXPECT_NEAR(m.psnr, 10.0 * std::log10(1.0 / (e * e)), 1e-9);  // about 20 dB
  // Flat images: only SSIM's luminance term differs from 1.
  const double c1 = 1e-4, a = 0.6f, b = 0.5f;
  EXPECT_NEAR(m.ssim, (2 * a * b + c1) / (a * a + b * b + c1), 1e-9);
}

TEST(ErrorMetrics, BiasIsSignedAndMaeIsNot) {
  auto im = constantImages(4, 1, 0.0f, 0.5f, 0.3f);
  im.output = {0.7f, 0.3f, 0.7f, 0.2f};  // errors +0.2, -0.2, +0.2, -0.3
  auto m = computeErrorMetrics(im.output.data(), im.reference.data(), im.depth.data(), 4, 1, false);
  EXPECT_NEAR(m.bias, (0.2 - 0.2 + 0.2 - 0.3) / 4, 1e-6);
  EXPECT_NEAR(m.mae, 0.9 / 4, 1e-6);
  EXPECT_NEAR(m.maxError, 0.3, 1e-6);
}

TEST(ErrorMetrics, Percentile99IsTheNearestRank) {
  // |e| = 0.01 * k for k = 1..200 in scrambled order: nearest rank ceil(0.99 * 200) = 198.
  auto im = constantImages(200, 1, 0.0f, 0.0f, 0.3f);
  for (int k = 1; k <= 200; ++k) im.output[size_t((k * 37) % 200)] = 0.001f * float(k);
  auto m = computeErrorMetrics(im.output.data(), im.reference.data(), im.depth.data(), 200, 1, false);
  EXPECT_FLOAT_EQ(float(m.p99), 0.001f * 198);
  EXPECT_FLOAT_EQ(float(m.maxError), 0.2f);
}

TEST(ErrorMetrics, SkyIsMaskedForStandardAndReversedDepth) {
  for (bool reversed : {false, true}) {
    float sky = reversed ? 0.0f : 1.0f;
    auto im = constantImages(8, 8, 0.5f, 0.5f, 0.4f);
    for (int i = 0; i < 8; ++i) {  // first row: sky with a wild output, must not count
      im.depth[size_t(i)] = sky;
      im.output[size_t(i)] = 0.0f;
      im.reference[size_t(i)] = 1.0f;
    }
    im.output[20] = 0.75f;  // one real error
    auto proj = reversed ? reversedProjection() : standardProjection();
    ASSERT_EQ(isReversedDepth(proj), reversed);
    auto m = computeErrorMetrics(im.output.data(), im.reference.data(), im.depth.data(), 8, 8, isReversedDepth(proj));
    EXPECT_EQ(m.pixels, 56) << "reversed " << reversed;
    EXPECT_NEAR(m.maxError, 0.25, 1e-7);
    EXPECT_NEAR(m.rmse, std::sqrt(0.25 * 0.25 / 56), 1e-7);
  }
}

TEST(ErrorMetrics, SsimFallsWithStructuralNoiseButNotWithNothing) {
  const int w = 32, h = 32;
  auto im = constantImages(w, h, 0.0f, 0.0f, 0.3f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) im.reference[size_t(y * w + x)] = 0.5f + 0.4f * std::sin(0.3f * float(x)) * std::cos(0.2f * float(y));
  im.output = im.reference;
  auto same = computeErrorMetrics(im.output.data(), im.reference.data(), im.depth.data(), w, h, false);
  for (size_t i = 0; i < im.output.size(); ++i) im.output[i] += (i * 2654435761u) % 3 == 0 ? 0.15f : -0.075f;
  auto noisy = computeErrorMetrics(im.output.data(), im.reference.data(), im.depth.data(), w, h, false);
  EXPECT_NEAR(same.ssim, 1.0, 1e-9);
  EXPECT_LT(noisy.ssim, 0.9);
  EXPECT_GT(noisy.ssim, 0.0);
}

TEST(ErrorAnalysis, FramesWithoutReferenceAreSkippedAndSummariesPool) {
  ErrorAnalysis analysis;
  auto a = constantImages(10, 10, 0.6f, 0.5f, 0.3f);  // 100 pixels, |e| 0.1
  auto b = constantImages(10, 30, 0.2f, 0.5f, 0.3f);  // 300 pixels, |e| 0.3, negative
  analysis.addFrame(frameOf(a, 0, a.reference, standardProjection()));
  AnalyzedFrame noReference = frameOf(a, 1, a.reference, standardProjection());
  noReference.reference = nullptr;
  analysis.addFrame(noReference);
  analysis.addFrame(frameOf(b, 2, b.reference, standardProjection()));

  EXPECT_TRUE(analysis.frameJson(1).is_null());
  EXPECT_NEAR(analysis.frameJson(0)["rmse"].get<double>(), 0.1, 1e-6);
  auto s = analysis.summaryJson();
  EXPECT_EQ(s["frames"].get<int>(), 2);
  EXPECT_EQ(s["pixels"].get<int>(), 400);
  double ea = double(0.6f) - double(0.5f), eb = double(0.2f) - double(0.5f);
  EXPECT_NEAR(s["rmse"].get<double>(), std::sqrt((100 * ea * ea + 300 * eb * eb) / 400), 1e-9);
  EXPECT_NEAR(s["bias"].get<double>(), (100 * ea + 300 * eb) / 400, 1e-9);
  EXPECT_NEAR(s["max"].get<double>(), -eb, 1e-9);
  EXPECT_NEAR(s["rmse_over_frames"]["max"].get<double>(), -eb, 1e-9);
  EXPECT_EQ(s["reference"], "ray-traced");
  EXPECT_TRUE(ErrorAnalysis().summaryJson().is_null());
}

namespace aor {
namespace {

// A plate 2 units away in front of a wall 6 units away: the wall next to the plate's edge is the
// halo band. The output is too open (+0.2) on the wall's left half only.
TEST(ErrorAnalysis, HaloBandIsTheBackgroundBehindASilhouetteWithinTheCapturesRadius) {
  const int w = 40, h = 20;
  glm::mat4 p = standardProjection();
  p[0][0] = p[1][1] = 1.0f;  // 20 pixels per unit at distance 1: a radius of 2 reaches 7 pixels at 6 units
  auto depthAt = [&](float distance) { return (p[2][2] * -distance + p[3][2]) / distance; };
  Images im = constantImages(w, h, 0.5f, 0.5f, depthAt(6.0f));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w / 2; ++x) {
      const size_t i = size_t(y * w + x);
      if (x < 10) im.depth[i] = depthAt(2.0f);  // the plate: columns 0-9
      else im.output[i] = 0.7f;                 // the wall next to it
    }
  ErrorAnalysis analysis;
  AnalyzedFrame frame = frameOf(im, 0, im.reference, p);
  frame.bandRadius = 2.0f;
  analysis.addFrame(frame);
  const auto band = analysis.frameJson(0)["halo_band"];
  EXPECT_EQ(band["radius"].get<double>(), 2.0);
  const int64_t pixels = band["pixels"].get<int64_t>();
  EXPECT_GT(pixels, 0);
  EXPECT_LT(pixels, int64_t(w * h / 2)) << "only the wall near the plate's edge";
  // Every band pixel lies on the wall's left half (columns 10-19), where the output is off by 0.2.
  EXPECT_NEAR(band["rmse"].get<double>(), double(0.7f) - double(0.5f), 1e-6);
  EXPECT_NEAR(band["bias"].get<double>(), double(0.7f) - double(0.5f), 1e-6);
  // A larger radius reaches farther from the edge.
  frame.bandRadius = 6.0f;
  ErrorAnalysis wider;
  wider.addFrame(frame);
  EXPECT_GT(wider.frameJson(0)["halo_band"]["pixels"].get<int64_t>(), pixels);
  // The summary pools the band over frames like every other error.
  analysis.addFrame(frameOf(im, 1, im.reference, p));
  EXPECT_EQ(analysis.summaryJson()["halo_band"]["pixels"].get<int64_t>(),
            pixels + analysis.frameJson(1)["halo_band"]["pixels"].get<int64_t>());
}

}  // namespace
}  // namespace aor
