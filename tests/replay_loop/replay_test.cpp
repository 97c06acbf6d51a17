// End-to-end replays on lavapipe with validation: determinism, history resets at cuts, and the
// GTAO pass against its CPU mirror.
#include <cmath>
#include <cstdio>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "capture/image_io.h"
#include "cpu/gtao_cpu.h"
#include "gpu_test_support.h"
#include "blocks/linearize_depth.h"
#include "shared_passes/camera.h"
#include "blocks/spatial_denoise.h"

namespace aor::test {
namespace {

TEST(Replay, SameCaptureAndSettingsGiveBitIdenticalOutputs) {
  auto capture = generatedCapture("boxes", "orbit", 96, 54, 4);
  GtaoSettings settings;
  auto first = replay(capture, settings);
  auto second = replay(capture, settings);
  ASSERT_EQ(first.frames.size(), 4u);
  ASSERT_EQ(second.frames.size(), 4u);
  for (size_t i = 0; i < first.frames.size(); ++i) {
    EXPECT_TRUE(bitIdentical(first.frames[i].visibility, second.frames[i].visibility)) << "frame " << i;
    EXPECT_TRUE(bitIdentical(first.frames[i].bent, second.frames[i].bent)) << "frame " << i;
  }
  // The output is not trivially constant: the boxes occlude the floor.
  float minVisibility = 1.0f;
  for (float v : first.frames[0].visibility) minVisibility = std::min(minVisibility, v);
  EXPECT_LT(minVisibility, 0.8f);
}

TEST(Replay, HistoryIsValidAfterTheFirstFrameAndResetAtACut) {
  auto capture = generatedCapture("boxes", "cut", 64, 36, 6);
  auto replayed = replay(capture, GtaoSettings{});
  Capture c = loadCapture(capture);
  ASSERT_EQ(replayed.result.frames.size(), c.frames.size());
  int cuts = 0;
  for (size_t i = 0; i < c.frames.size(); ++i) {
    const auto& f = replayed.result.frames[i];
    if (i == 0) {
      EXPECT_EQ(f.resetReason, "first frame");
    } else if (c.frames[i].cut) {
      ++cuts;
      EXPECT_EQ(f.resetReason, "cut") << "frame " << i;
    } else {
      EXPECT_TRUE(f.historyValid) << "frame " << i << ": " << f.resetReason;
    }
  }
  EXPECT_EQ(cuts, 1);
}

TEST(Replay, FrameAfterACutEqualsThatFrameReplayedAlone) {
  auto capture = generatedCapture("boxes", "cut", 64, 36, 6);
  int k = cutFrame(loadCapture(capture));
  ASSERT_GT(k, 0);
  GtaoSettings settings;
  auto full = replay(capture, settings);
  auto alone = replay(capture, settings, k, k + 1);
  ASSERT_EQ(alone.frames.size(), 1u);
  EXPECT_TRUE(bitIdentical(full.frames[size_t(k)].visibility, alone.frames[0].visibility));
  EXPECT_TRUE(bitIdentical(full.frames[size_t(k)].bent, alone.frames[0].bent));
  // And the frame before the cut does blend history, so the check above is not vacuous.
  auto aloneBefore = replay(capture, settings, k - 1, k);
  EXPECT_FALSE(bitIdentical(full.frames[size_t(k - 1)].visibility, aloneBefore.frames[0].visibility));
}

TEST(Replay, DisablingTheResetAtACutLeaksHistory) {
  auto capture = generatedCapture("boxes", "cut", 64, 36, 6);
  int k = cutFrame(loadCapture(capture));
  GtaoSettings settings;
  settings.temporal = 0.98f;  // no rejection layer can hide a leak completely at this weight
  auto leaky = replay(capture, settings, 0, -1, /*keepHistoryOnCut=*/true);
  auto alone = replay(capture, settings, k, k + 1);
  EXPECT_TRUE(leaky.result.frames[size_t(k)].historyValid);
  EXPECT_FALSE(bitIdentical(leaky.frames[size_t(k)].visibility, alone.frames[0].visibility));
}

TEST(Replay, GtaoPassMatchesItsCpuMirror) {
  struct Case { bool bent; int slices, steps; };
  // 6x8 is past kGtaoMaxUnrolledSliceSteps: the shader's rolled slice loop, the presets' unrolled one.
  static_assert(6 * 8 > shader::kGtaoMaxUnrolledSliceSteps && 3 * 3 <= shader::kGtaoMaxUnrolledSliceSteps);
  for (Case c : {Case{true, 3, 3}, Case{false, 3, 3}, Case{true, 6, 8}}) {
    bool bent = c.bent;
    auto capturePath = generatedCapture("boxes", "orbit", 80, 45, 2);
    GtaoSettings settings = gtaoOnly();
    settings.bent = bent ? 1 : 0;
    settings.slices = c.slices;
    settings.steps = c.steps;
    settings.thin = 0.5f;
    auto gpu = replay(capturePath, settings, 1, 2);
    Capture capture = loadCapture(capturePath);
    const auto& frame = capture.frames[1];
    FrameCamera camera{frame.view, frame.projection, capture.width, capture.height, 1};
    auto cpu = gtaoOnCpu(loadGBuffer(capture, 1), camera, settings);
    ASSERT_EQ(cpu.visibility.size(), gpu.frames[0].visibility.size());
    double maxError = 0, minVisibility = 1;
    size_t worst = 0;
    for (size_t i = 0; i < cpu.visibility.size(); ++i) {
      double e = std::abs(double(cpu.visibility[i]) - double(gpu.frames[0].visibility[i]));
      if (e > maxError) { maxError = e; worst = i; }
      minVisibility = std::min(minVisibility, double(cpu.visibility[i]));
    }
    EXPECT_LE(maxError, 1e-3) << "bent=" << bent << " " << c.slices << "x" << c.steps << " worst pixel " << worst;
    EXPECT_LT(minVisibility, 0.7);  // the boxes occlude the floor: a constant output fails
    if (bent) {
      double maxBentError = 0;
      for (size_t i = 0; i < cpu.bent.size(); ++i)
        for (int c = 0; c < 3; ++c)
          maxBentError = std::max(maxBentError, std::abs(double(cpu.bent[i][c]) - double(gpu.frames[0].bent[3 * i + size_t(c)])));
      EXPECT_LE(maxBentError, 2e-3);
    }
  }
}

// The seed's spatial blur written out directly: 25 taps, each weighted by the Gaussian and by the
// edge weights along its grid path (horizontal leg from the centre, then vertical). The GPU runs it
// separated into two dispatches; this checks the separation changes nothing but rounding.
struct DirectBlur {
  int width, height;
  const std::vector<float>& distance;
  const FrameOutput& noisy;

  size_t index(int x, int y) const { return size_t(y) * size_t(width) + size_t(x); }
  float pathWeight(int x0, int y0, int dx, int dy) const {  // walk (x0,y0) -> (x0+dx,y0) -> (x0+dx,y0+dy)
    float w = 1.0f;
    for (int k = 1; k <= std::abs(dx); ++k) {
      int step = dx > 0 ? 1 : -1;
      w *= shader::depthEdgeWeight(distance[index(x0 + (k - 1) * step, y0)], distance[index(x0 + k * step, y0)]);
    }
    for (int k = 1; k <= std::abs(dy); ++k) {
      int step = dy > 0 ? 1 : -1;
      w *= shader::depthEdgeWeight(distance[index(x0 + dx, y0 + (k - 1) * step)], distance[index(x0 + dx, y0 + k * step)]);
    }
    return w;
  }
  glm::vec4 at(int x, int y) const {
    size_t c = index(x, y);
    glm::vec4 centre(noisy.bent[3 * c], noisy.bent[3 * c + 1], noisy.bent[3 * c + 2], noisy.visibility[c]);
    if (distance[c] <= 0.0f) return centre;
    glm::vec4 sum(0.0f);
    float weightSum = 0.0f;
    for (int dy = -shader::kSpatialRadius; dy <= shader::kSpatialRadius; ++dy)
      for (int dx = -shader::kSpatialRadius; dx <= shader::kSpatialRadius; ++dx) {
        int tx = x + dx, ty = y + dy;
        if (tx < 0 || ty < 0 || tx >= width || ty >= height) continue;
        float w = shader::spatialGaussian(dx, dy) * pathWeight(x, y, dx, dy);
        size_t t = index(tx, ty);
        sum += w * glm::vec4(noisy.bent[3 * t], noisy.bent[3 * t + 1], noisy.bent[3 * t + 2], noisy.visibility[t]);
        weightSum += w;
      }
    glm::vec4 result = sum / weightSum;
    float len = glm::length(glm::vec3(result));
    return glm::vec4(len > 1e-6f ? glm::vec3(result) / len : glm::vec3(centre), result.w);
  }
};

TEST(Replay, SpatialPassIsTheSeedsPathWeighted5x5Blur) {
  auto capturePath = generatedCapture("boxes", "orbit", 80, 45, 2);
  GtaoSettings settings = gtaoOnly();
  auto noisy = replay(capturePath, settings, 1, 2);
  settings.spatial = 1;
  auto blurred = replay(capturePath, settings, 1, 2);
  Capture capture = loadCapture(capturePath);
  auto params = projectionParams(capture.frames[1].projection, capture.width, capture.height);
  auto gbuffer = loadGBuffer(capture, 1);
  std::vector<float> distance(gbuffer.depth.size());
  for (size_t i = 0; i < distance.size(); ++i)
    distance[i] = shader::linearViewDistance(gbuffer.depth[i], params.projection22, params.projection32, params.reversedDepth);

  DirectBlur direct{capture.width, capture.height, distance, noisy.frames[0]};
  const auto& gpu = blurred.frames[0];
  double maxError = 0, maxBentError = 0, maxChange = 0;
  for (int y = 0; y < capture.height; ++y)
    for (int x = 0; x < capture.width; ++x) {
      size_t i = direct.index(x, y);
      glm::vec4 expected = direct.at(x, y);
      maxError = std::max(maxError, std::abs(double(expected.w) - double(gpu.visibility[i])));
      for (int c = 0; c < 3; ++c)
        maxBentError = std::max(maxBentError, std::abs(double(expected[c]) - double(gpu.bent[3 * i + size_t(c)])));
      maxChange = std::max(maxChange, std::abs(double(noisy.frames[0].visibility[i]) - double(gpu.visibility[i])));
    }
  std::printf("spatial vs direct 25-tap: max %.2e, bent %.2e, change %.3f\n", maxError, maxBentError, maxChange);
  // Half-float column sums, edge weights and output: about 1e-3 at most.
  EXPECT_LE(maxError, 2e-3);
  EXPECT_LE(maxBentError, 2e-3);
  EXPECT_GT(maxChange, 0.02) << "the blur must change the noisy AO, or this test proves nothing";
}

TEST(Replay, FlatPlaneHasNoSelfOcclusion) {
  struct Case { float pitch; bool reversed, infinite; };
  for (Case c : {Case{30, false, false}, Case{60, true, false}, Case{10, false, true}, Case{5, true, true}}) {
    PlaneCaptureOptions o;
    o.pitchDegrees = c.pitch;
    o.reversedZ = c.reversed;
    o.infiniteFar = c.infinite;
    auto capture = planeCapture(fmt::format("plane-{}-{}-{}", c.pitch, c.reversed, c.infinite), o);
    GtaoSettings settings = gtaoOnly();
    settings.slices = 9;
    auto out = replay(capture, settings);
    float minVisibility = 1.0f;
    for (float v : out.frames[0].visibility) minVisibility = std::min(minVisibility, v);
    EXPECT_GE(minVisibility, 0.99f) << "pitch " << c.pitch << " reversed " << c.reversed << " infinite " << c.infinite;
  }
}

TEST(Replay, DepthOnlyCaptureReconstructsNormalsCloseToTheTrueOnes) {
  auto withNormals = generatedCapture("boxes", "orbit", 64, 36, 1, true);
  auto depthOnly = generatedCapture("boxes", "orbit", 64, 36, 1, false);
  auto a = replay(withNormals, gtaoOnly());
  auto b = replay(depthOnly, gtaoOnly());
  double meanDifference = 0;
  for (size_t i = 0; i < a.frames[0].visibility.size(); ++i)
    meanDifference += std::abs(a.frames[0].visibility[i] - b.frames[0].visibility[i]);
  meanDifference /= double(a.frames[0].visibility.size());
  EXPECT_LT(meanDifference, 0.05);
  bool reconstructionRan = false;
  for (const auto& p : b.result.frames[0].passes) reconstructionRan |= p.name == "reconstruct_normals";
  EXPECT_TRUE(reconstructionRan);
}

}  // namespace
}  // namespace aor::test
