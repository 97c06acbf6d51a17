// Temporal stability on the shipped temporal captures (captures/boxes-static, -strafe, -cut):
// flicker falls as the denoisers are switched on, history never survives an invalidation (marked
// cut or unmarked camera jump beyond the limits), the disocclusion response stays within what the EMA weight allows,
// and `--expect` fails a run with a readable list.
#include <filesystem>
#include <fstream>
#include <regex>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "gpu_test_support.h"
#include "metrics/temporal_metrics.h"
#include "metrics/temporal_response.h"
#include "replay_loop/camera_jump.h"
#include "report/expectations.h"

namespace aor::test {
namespace {
namespace fs = std::filesystem;

fs::path shipped(const std::string& name) { return fs::path(AOR_SOURCE_DIR) / "captures" / name; }

// Replays `capture` in-process and feeds every frame to a TemporalAnalysis, as `aoreplay run` does;
// with `againstNoHistory` errors are measured against a temporal=0 replay instead of the reference.
TemporalAnalysis analyze(const fs::path& capturePath, const GtaoSettings& settings, bool againstNoHistory = false) {
  Capture capture = loadCapture(capturePath);
  auto replayed = replay(capturePath, settings);
  GtaoSettings withoutHistory = settings;
  withoutHistory.temporal = 0;
  std::vector<FrameOutput> noHistory;
  if (againstNoHistory) noHistory = replay(capturePath, withoutHistory).frames;
  TemporalAnalysis analysis;
  for (const auto& frame : replayed.frames) {
    const auto& desc = capture.frames[size_t(frame.index)];
    GBuffer g = loadGBuffer(capture, frame.index);
    auto reference = againstNoHistory ? std::nullopt : loadReference(capture, frame.index);
    AnalyzedFrame a{frame.index, frame.width, frame.height, frame.visibility.data(), g.depth.data(), desc.view,
                    desc.projection, desc.cut, frame.historyValid, frame.resetReason, reference ? &*reference : nullptr};
    a.historyWeight = settings.temporal;
    if (againstNoHistory) a.noHistory = noHistory[size_t(frame.index)].visibility.data();
    analysis.addFrame(a);
  }
  return analysis;
}

TEST(Temporal, StaticNoiseFallsWithTheSpatialAndAgainWithTheTemporalPass) {
  GtaoSettings raw, spatialOnly, full;
  raw.spatial = 0;
  raw.temporal = 0;
  spatialOnly.temporal = 0;
  auto noiseRaw = analyze(shipped("boxes-static"), raw).staticNoise();
  auto noiseSpatial = analyze(shipped("boxes-static"), spatialOnly).staticNoise();
  auto noiseFull = analyze(shipped("boxes-static"), full).staticNoise();
  ASSERT_EQ(noiseFull.pixels, noiseRaw.pixels);
  ASSERT_GT(noiseFull.pixels, 1000u);  // one 16-frame window over the whole surface
  std::printf("static temporal noise (mean / p99): temporal=0 spatial=0 %.5f / %.5f, spatial only %.5f / %.5f, "
              "spatial+temporal(0.9) %.5f / %.5f; factors vs temporal=0: %.1fx (spatial only), %.1fx (temporal on)\n",
              noiseRaw.mean, noiseRaw.p99, noiseSpatial.mean, noiseSpatial.p99, noiseFull.mean, noiseFull.p99,
              noiseRaw.mean / noiseSpatial.mean, noiseRaw.mean / noiseFull.mean);
  // An EMA with w = 0.9 over a 16-frame window keeps well under half the deviation of its input;
  // demanding 2x on each step leaves room for the spatially correlated part of the noise.
  EXPECT_LT(noiseFull.mean * 2.0, noiseSpatial.mean);
  EXPECT_LT(noiseSpatial.mean * 2.0, noiseRaw.mean);
  EXPECT_LT(noiseFull.p99, noiseSpatial.p99);
  EXPECT_LT(noiseSpatial.p99, noiseRaw.p99);
}

// The shipped cut capture with the cut flag removed: the jump must be caught by the camera limits.
fs::path unmarkedCutCapture() {
  fs::path dir = scratchDir("temporal-unmarked-cut");
  fs::copy(shipped("boxes-cut"), dir, fs::copy_options::recursive | fs::copy_options::overwrite_existing);
  std::ifstream in(dir / "capture.json");
  auto j = nlohmann::json::parse(in);
  in.close();
  for (auto& f : j["frames"]) f.erase("cut");
  std::ofstream(dir / "capture.json") << j.dump(2);
  return dir;
}

TEST(Temporal, FrameAfterTheShippedCutEqualsAReplayStartingThere) {
  auto path = shipped("boxes-cut");
  int k = cutFrame(loadCapture(path));
  ASSERT_GT(k, 1);
  GtaoSettings settings;
  auto full = replay(path, settings);
  auto fromCut = replay(path, settings, k, -1);
  EXPECT_EQ(full.result.frames[size_t(k)].resetReason, "cut");
  // Every frame from the cut on, not only the first: history after the cut is built from post-cut frames only.
  for (size_t i = 0; i < fromCut.frames.size(); ++i)
    EXPECT_TRUE(bitIdentical(full.frames[size_t(k) + i].visibility, fromCut.frames[i].visibility)) << "frame " << k + int(i);
  // The test-only switch that keeps history across the cut makes the same check fail.
  settings.temporal = 0.98f;
  auto leaky = replay(path, settings, 0, -1, /*keepHistoryOnCut=*/true);
  auto alone = replay(path, settings, k, k + 1);
  EXPECT_FALSE(bitIdentical(leaky.frames[size_t(k)].visibility, alone.frames[0].visibility));
}

// Replays with explicit camera-jump limits; returns the result and frame `keep`'s visibility.
std::pair<ReplayResult, std::vector<float>> replayWithJumpLimits(const fs::path& path, const GtaoSettings& settings,
                                                                  CameraJumpLimits limits, int keep) {
  ReplayOptions options(settingsOf(gtaoTechnique(), settings));
  options.cameraJump = limits;
  std::vector<float> kept;
  auto result = replayCapture(validatedContext(), loadCapture(path), options, [&](const FrameOutput& f) {
    if (f.index == keep) kept = f.visibility;
  });
  return {std::move(result), std::move(kept)};
}

TEST(Temporal, AnUnmarkedCameraJumpBeyondTheLimitResetsHistory) {
  auto path = unmarkedCutCapture();
  int k = cutFrame(loadCapture(shipped("boxes-cut")));
  ASSERT_EQ(cutFrame(loadCapture(path)), -1);
  GtaoSettings settings;
  settings.temporal = 0.98f;  // no rejection layer can hide a leak completely at this weight
  // The jump turns the camera 22 degrees; the orbits around it turn under 1.5 per frame.
  auto [caught, afterJump] = replayWithJumpLimits(path, settings, {20.0f, 0.0f}, k);
  for (size_t i = 1; i < caught.frames.size(); ++i) {
    const auto& f = caught.frames[i];
    if (int(i) == k) {
      EXPECT_EQ(f.resetReason.rfind("camera jump: turned 22.", 0), 0u) << f.resetReason;
    } else {
      EXPECT_TRUE(f.historyValid) << "frame " << i << ": " << f.resetReason;
    }
  }
  auto alone = replay(path, settings, k, k + 1);
  EXPECT_TRUE(bitIdentical(afterJump, alone.frames[0].visibility));
  // With the limits off nothing catches it: history leaks into the frame after the jump.
  auto [missed, leaked] = replayWithJumpLimits(path, settings, {0.0f, 0.0f}, k);
  EXPECT_TRUE(missed.frames[size_t(k)].historyValid);
  EXPECT_FALSE(bitIdentical(leaked, alone.frames[0].visibility));
}

TEST(Temporal, DefaultJumpLimitsCatchWhatNoSmoothCameraDoes) {
  auto look = [](glm::vec3 eye, glm::vec3 at) { return glm::lookAtRH(eye, at, glm::vec3(0, 1, 0)); };
  glm::mat4 start = look({0, 2, 10}, {0, 0, 0});
  CameraJumpLimits defaults;
  // Distances: the previous frame's median view distance is 10.
  EXPECT_EQ(cameraJumpReason(start, look({0, 2, 10}, {3, 0, 0}), 10.0f, defaults), "");  // a 17-degree pan
  EXPECT_EQ(cameraJumpReason(start, look({0, 2, 2}, {0, 0, -8}), 10.0f, defaults), "");  // 8 units forward
  auto turned = cameraJumpReason(start, look({0, 2, 10}, {0, 2, 20}), 10.0f, defaults);  // turned around
  EXPECT_EQ(turned.rfind("camera jump: turned 1", 0), 0u) << turned;
  auto moved = cameraJumpReason(start, look({0, 2, -5}, {0, 0, -15}), 10.0f, defaults);  // 15 units
  EXPECT_EQ(moved, "camera jump: moved 15 (limit 1 x median view distance 10)");
  EXPECT_EQ(cameraJumpReason(start, look({0, 2, -5}, {0, 0, -15}), 10.0f, {0.0f, 0.0f}), "");
}

TEST(Temporal, DisocclusionResponseOnTheStrafeStaysWithinTheEmaBound) {
  GtaoSettings settings;
  settings.temporal = 0.6f;  // predicts 5 frames to 10%, so the 16-frame strafe shows the settled tail
  auto analysis = analyze(shipped("boxes-strafe"), settings);
  auto d = analysis.summaryJson()["disocclusion"];
  ASSERT_FALSE(d.is_null());
  int predicted = emaResponseFrames(settings.temporal);
  int response = d["response_frames"].get<int>(), emaForCurve = d["ema_response_frames"].get<int>();
  std::printf("strafe, w=0.6: disocclusion response %d frames (EMA: %d for a full ghost, %d for this curve's "
              "initial excess), ghost energy %.4f, settled error %.4f over %zu ages, %s pixels disoccluded\n",
              response, predicted, emaForCurve, d["ghost_energy"].get<double>(), d["settled_error"].get<double>(),
              d["abs_error_by_age"].size(), d["pixels_by_age"][0].dump().c_str());
  EXPECT_TRUE(d["settled"].get<bool>()) << "the curve must reach past the EMA's predicted response";
  EXPECT_GE(d["pixels_by_age"][0].get<size_t>(), 1000u) << "the strafe disoccludes";
  // Margin of 2 frames: the history is read bilinearly, so a pixel next to a disocclusion edge mixes
  // up to one texel of a neighbour's history for one more frame, and the settled value is a 3-frame
  // tail mean whose own noise can put one extra frame outside the 10% band.
  constexpr int kMarginFrames = 2;
  EXPECT_LE(response, emaForCurve + kMarginFrames);
  EXPECT_LE(response, predicted + kMarginFrames);
}

// Against a no-history replay, every pixel the metric calls disoccluded must be exactly the fresh
// value on its first frame (the pass rejected its history: the metric's mask and the shader's
// agree), and the deviation appears at the first blended frame (w of the output is history at once).
TEST(Temporal, DisoccludedPixelsAreExactlyTheFreshValueOnTheirFirstFrame) {
  GtaoSettings settings;
  settings.temporal = 0.6f;
  auto analysis = analyze(shipped("boxes-strafe"), settings, /*againstNoHistory=*/true);
  auto summary = analysis.summaryJson();
  EXPECT_EQ(summary["error_source"], "no-history replay");
  auto d = summary["disocclusion"];
  ASSERT_FALSE(d.is_null());
  EXPECT_EQ(d["abs_error_by_age"][0].get<double>(), 0.0);
  int predicted = emaResponseFrames(settings.temporal), response = d["response_frames"].get<int>();
  std::printf("strafe vs no-history replay, w=0.6: response %d frames (EMA %d), curve %s\n", response, predicted,
              d["abs_error_by_age"].dump().c_str());
  EXPECT_LE(response, predicted + 2);  // margin as in the test above
}

TEST(Temporal, ExpectationsNameTheMetricTheFrameAndBothNumbers) {
  nlohmann::json report = nlohmann::json::parse(R"({
    "frames": [{"index": 3, "gpu_ms_median": {"gtao": 2.5}, "metrics": {"temporal": {"warping_error": 0.004}}},
               {"index": 4, "gpu_ms_median": {"gtao": 1.5}, "metrics": {"temporal": {"warping_error": 0.001}}}],
    "passes": [{"name": "gtao", "gpu_ms": {"median": 2.0}}],
    "metrics": {"temporal": {"static_noise": {"mean": 0.02}}}})");
  std::vector<Threshold> thresholds{{"temporal.warping_error", true, 0.002}, {"gpu_ms.gtao", true, 2.2},
                                    {"temporal.static_noise.mean", false, 0.05}};
  auto failures = checkExpectations(thresholds, report, "x.json");
  ASSERT_EQ(failures.size(), 3u);
  EXPECT_EQ(failures[0].describe(), "temporal.warping_error at frame 3: 0.004 > max 0.002");
  EXPECT_EQ(failures[1].describe(), "gpu_ms.gtao at frame 3: 2.5 > max 2.2");
  EXPECT_EQ(failures[2].describe(), "temporal.static_noise.mean over the run: 0.02 < min 0.05");
  EXPECT_THROW(checkExpectations({{"temporal.warping_eror", true, 1}}, report, "x.json"), InputError);
}

TEST(Temporal, ExpectFailsTheRunAfterWritingItsOutputs) {
  auto dir = scratchDir("temporal-expect");
  std::ofstream(dir / "strict.json") << R"({"max": {"temporal.warping_error": 1e-9, "temporal.static_noise.mean": 1}})";
  auto out = dir / "result";
  auto r = runAoreplay(fmt::format("run {} --frames 0:4 --no-images --out {} --expect {}", shipped("boxes-static").string(),
                                   out.string(), (dir / "strict.json").string()));
  EXPECT_EQ(r.exitCode, 1) << r.output;
  // One line per violating frame: metric, frame, measured value, limit.
  std::regex line(R"(temporal\.warping_error at frame [123]: [0-9.e+-]+ > max 1e-09)");
  EXPECT_EQ(std::distance(std::sregex_iterator(r.output.begin(), r.output.end(), line), std::sregex_iterator()), 3) << r.output;
  EXPECT_EQ(r.output.find("static_noise"), std::string::npos) << "a met threshold is not listed";
  EXPECT_TRUE(fs::exists(out / "report.json"));
  EXPECT_TRUE(fs::exists(out / "temporal.svg"));

  std::ofstream(dir / "loose.json") << R"({"max": {"temporal.warping_error": 1, "temporal.static_noise.p99": 1}})";
  r = runAoreplay(fmt::format("run {} --frames 0:4 --no-images --out {} --expect {}", shipped("boxes-static").string(),
                              out.string(), (dir / "loose.json").string()));
  EXPECT_EQ(r.exitCode, 0) << r.output;

  std::ofstream(dir / "typo.json") << R"({"max": {"temporal.warping_eror": 1}})";
  auto typoOut = dir / "typo-result";
  r = runAoreplay(fmt::format("run {} --frames 0:4 --no-images --out {} --expect {}", shipped("boxes-static").string(),
                              typoOut.string(), (dir / "typo.json").string()));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("max.temporal.warping_eror"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(typoOut)) << "nothing is left looking valid";
}

TEST(Temporal, WithoutReferencesTheRunComparesWithANoHistoryReplay) {
  auto capture = generatedCapture("boxes", "strafe", 64, 36, 5);  // generated without references
  auto out = scratchDir("temporal-no-reference") / "result";
  auto r = runAoreplay(fmt::format("run {} --no-images --out {}", capture.string(), out.string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::ifstream in(out / "report.json");
  auto report = nlohmann::json::parse(in);
  EXPECT_EQ(report["metrics"]["temporal"]["error_source"], "no-history replay");
  EXPECT_EQ(report["frames"][0]["metrics"]["temporal"]["abs_error"].get<double>(), 0.0);  // first frame: no history
  EXPECT_GT(report["frames"][1]["metrics"]["temporal"]["abs_error"].get<double>(), 0.0);
}

TEST(Temporal, ReportSaysWhyHistoryWasResetAndDrawsThePlots) {
  auto out = scratchDir("temporal-report") / "result";
  auto r = runAoreplay(fmt::format("run {} --no-images --out {} --set temporal=0.6", shipped("boxes-strafe").string(), out.string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::ifstream in(out / "report.json");
  auto report = nlohmann::json::parse(in);
  EXPECT_EQ(report["frames"][0]["reset_reason"], "first frame");
  EXPECT_EQ(report["frames"][1]["history"], "valid");
  EXPECT_TRUE(report["frames"][1]["metrics"]["temporal"].contains("warping_error"));
  EXPECT_TRUE(report["frames"][1]["metrics"]["temporal"].contains("derivative_error"));
  EXPECT_EQ(report["metrics"]["temporal"]["error_source"], "reference");
  EXPECT_TRUE(fs::exists(out / "temporal.svg"));
  EXPECT_TRUE(fs::exists(out / "temporal_response.svg"));
}

}  // namespace
}  // namespace aor::test
