// half_res=1 (shaders/docs/guide.md, "half_res"): GTAO on one pixel of each 2x2 block against
// its CPU mirror, the upsample's bounds, determinism and cuts, and the error it costs against the
// ray-traced reference.
#include <algorithm>
#include <cmath>
#include <fstream>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "capture/image_io.h"
#include "cpu/gtao_cpu.h"
#include "gpu_test_support.h"
#include "metrics/depth.h"

namespace aor::test {
namespace {

// No denoiser: the output is GTAO's half-resolution image through the `upsample` pass alone.
GtaoSettings halfResolutionGtaoOnly() {
  GtaoSettings s = gtaoOnly();
  s.halfRes = 1;
  return s;
}

// 81x45: odd width and height, so the last column and row have texels of their own.
constexpr int kWidth = 81, kHeight = 45;

struct Frame {
  FrameOutput gpu;
  std::vector<float> distance;
  FrameCamera camera;
};

Frame replayFrameOne(const GtaoSettings& settings) {
  auto path = generatedCapture("boxes", "orbit", kWidth, kHeight, 2);
  Capture capture = loadCapture(path);
  const auto& f = capture.frames[1];
  Frame frame{replay(path, settings, 1, 2).frames.at(0), {}, {f.view, f.projection, capture.width, capture.height, 1}};
  frame.distance = linearViewDistances(loadGBuffer(capture, 1).depth, f.projection);
  return frame;
}

size_t index(int x, int y) { return size_t(y) * size_t(kWidth) + size_t(x); }

TEST(HalfResolution, GtaoMatchesItsCpuMirrorAtTheEvaluatedPixels) {
  GtaoSettings settings = halfResolutionGtaoOnly();
  Frame frame = replayFrameOne(settings);
  auto path = generatedCapture("boxes", "orbit", kWidth, kHeight, 2);
  auto cpu = gtaoOnCpu(loadGBuffer(loadCapture(path), 1), frame.camera, settings);
  ASSERT_EQ(cpu.width, (kWidth + 1) / 2);
  ASSERT_EQ(cpu.height, (kHeight + 1) / 2);
  ASSERT_EQ(frame.gpu.visibility.size(), size_t(kWidth) * kHeight);
  double maxError = 0, maxBentError = 0, minVisibility = 1;
  for (int ty = 0; ty < cpu.height; ++ty)
    for (int tx = 0; tx < cpu.width; ++tx) {
      size_t t = size_t(ty) * size_t(cpu.width) + size_t(tx), p = index(2 * tx, 2 * ty);
      maxError = std::max(maxError, std::abs(double(cpu.visibility[t]) - double(frame.gpu.visibility[p])));
      for (int c = 0; c < 3; ++c)
        maxBentError = std::max(maxBentError, std::abs(double(cpu.bent[t][c]) - double(frame.gpu.bent[3 * p + size_t(c)])));
      minVisibility = std::min(minVisibility, double(cpu.visibility[t]));
    }
  // The bounds of GtaoPassMatchesItsCpuMirror: half-float storage and device arithmetic.
  EXPECT_LE(maxError, 1e-3);
  EXPECT_LE(maxBentError, 2e-3);
  EXPECT_LT(minVisibility, 0.7);  // the boxes occlude the floor: a constant output fails

  // The noise follows the texel: the same texel computed with pixel 2t's noise differs.
  GtaoSettings full = settings;
  full.halfRes = 0;
  auto fullCpu = gtaoOnCpu(loadGBuffer(loadCapture(path), 1), frame.camera, full);
  int differing = 0;
  for (int ty = 0; ty < cpu.height; ++ty)
    for (int tx = 0; tx < cpu.width; ++tx)
      differing += cpu.visibility[size_t(ty) * size_t(cpu.width) + size_t(tx)] != fullCpu.visibility[index(2 * tx, 2 * ty)];
  EXPECT_GT(differing, cpu.width * cpu.height / 4);
}

// Every pixel between evaluated ones is a weighted mean of the (up to four) texels around it, so
// its visibility lies within theirs; sky pixels get what GTAO writes for sky.
TEST(HalfResolution, UpsampledPixelsLieWithinTheirNeighbouringTexels) {
  Frame frame = replayFrameOne(halfResolutionGtaoOnly());
  const auto& v = frame.gpu.visibility;
  int checked = 0, spread = 0, sky = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      if (x % 2 == 0 && y % 2 == 0) continue;  // evaluated: the mirror test's
      if (frame.distance[index(x, y)] <= 0.0f) {
        EXPECT_EQ(v[index(x, y)], 1.0f) << "sky at " << x << "," << y;
        ++sky;
        continue;
      }
      // The evaluated pixels of the texels around (x, y), clamped at the last texel.
      int x0 = x / 2 * 2, y0 = y / 2 * 2;
      int x1 = std::min(x0 + (x % 2) * 2, (kWidth - 1) / 2 * 2), y1 = std::min(y0 + (y % 2) * 2, (kHeight - 1) / 2 * 2);
      float lo = std::min({v[index(x0, y0)], v[index(x1, y0)], v[index(x0, y1)], v[index(x1, y1)]});
      float hi = std::max({v[index(x0, y0)], v[index(x1, y0)], v[index(x0, y1)], v[index(x1, y1)]});
      // One half-float step of slack: the mean is rounded in float, then stored as a half float
      // (lavapipe truncates: 0.99951 blended with itself can be stored as 0.99902).
      const float kHalfStep = 1.0f / 2048.0f;
      EXPECT_GE(v[index(x, y)], lo - kHalfStep) << x << "," << y;
      EXPECT_LE(v[index(x, y)], hi + kHalfStep) << x << "," << y;
      ++checked;
      spread += hi - lo > 0.05f;
    }
  EXPECT_EQ(checked + sky, kWidth * kHeight - ((kWidth + 1) / 2) * ((kHeight + 1) / 2));
  EXPECT_GT(spread, 100) << "the bound must be checked where the texels differ";
}

// A floor seen at 10 degrees below the horizon: sky above it, at odd and even pixels alike.
TEST(HalfResolution, SkyPixelsGetWhatGtaoWritesForSky) {
  PlaneCaptureOptions options;
  options.width = 63;
  options.height = 35;
  options.pitchDegrees = 10.0f;
  auto path = planeCapture("half-res-plane", options);
  Capture capture = loadCapture(path);
  auto distance = linearViewDistances(loadGBuffer(capture, 0).depth, capture.frames[0].projection);
  auto out = replay(path, halfResolutionGtaoOnly()).frames.at(0);
  int sky = 0;
  for (size_t i = 0; i < distance.size(); ++i) {
    if (distance[i] > 0.0f) continue;
    ++sky;
    EXPECT_EQ(out.visibility[i], 1.0f) << "pixel " << i;
    EXPECT_EQ(out.bent[3 * i + 2], 1.0f) << "pixel " << i;
  }
  EXPECT_GT(sky, 63 * 4);
}

TEST(HalfResolution, ReplayIsBitIdenticalAndAFrameAfterACutEqualsItAlone) {
  auto capture = generatedCapture("boxes", "cut", 64, 36, 6);
  Capture c = loadCapture(capture);
  int k = cutFrame(c);
  ASSERT_GT(k, 0);
  GtaoSettings settings;
  settings.halfRes = 1;
  auto first = replay(capture, settings);
  auto second = replay(capture, settings);
  GtaoSettings fullSettings;
  auto full = replay(capture, fullSettings);
  ASSERT_EQ(first.frames.size(), c.frames.size());
  for (size_t i = 0; i < first.frames.size(); ++i) {
    EXPECT_TRUE(bitIdentical(first.frames[i].visibility, second.frames[i].visibility)) << "frame " << i;
    EXPECT_TRUE(bitIdentical(first.frames[i].bent, second.frames[i].bent)) << "frame " << i;
    EXPECT_FALSE(bitIdentical(first.frames[i].visibility, full.frames[i].visibility)) << "half_res changed nothing";
  }
  auto alone = replay(capture, settings, k, k + 1);
  EXPECT_TRUE(bitIdentical(first.frames[size_t(k)].visibility, alone.frames[0].visibility));
  EXPECT_TRUE(bitIdentical(first.frames[size_t(k)].bent, alone.frames[0].bent));
  EXPECT_TRUE(first.result.frames[size_t(k - 1)].historyValid);
}

// The quality half_res trades for time, on the shipped sphere and boxes captures against their
// ray-traced references (measured: RMSE +0.2 % and +1.9 %, bench/RESULTS.md).
TEST(HalfResolution, ErrorStaysWithinFivePercentOfFullResolution) {
  for (const char* name : {"sphere-orbit", "boxes-orbit"}) {
    auto out = scratchDir(fmt::format("half-res-sweep-{}", name)) / "result";
    auto capture = std::filesystem::path(AOR_SOURCE_DIR) / "captures" / name;
    auto run = runAoreplay(fmt::format("sweep {} --presets high --grid half_res=0,1 --frames 0:4 --repeat 1 --warmup 0 --out {}",
                                       capture.string(), out.string()));
    ASSERT_EQ(run.exitCode, 0) << run.output;
    std::ifstream in(out / "sweep.json");
    auto rows = nlohmann::json::parse(in)["rows"];
    ASSERT_EQ(rows.size(), 2u);
    EXPECT_EQ(rows[1]["settings"]["half_res"], 1);
    EXPECT_TRUE(rows[1]["gpu_ms_median"].contains("temporal"));
    double full = rows[0]["rmse"].get<double>(), half = rows[1]["rmse"].get<double>();
    fmt::print("{}: RMSE full {:.5f}, half_res {:.5f}\n", name, full, half);
    EXPECT_NE(half, full);
    EXPECT_LE(half, 1.05 * full) << name;
  }
}

}  // namespace
}  // namespace aor::test
