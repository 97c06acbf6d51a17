// XeGTAO (seed 002, --technique xegtao): every depth format, denoise pass count and option under
// validation; bit-identity; the noise keyed to the capture's frame index; the depth MIP chain
// really sampled at its coarse levels (the Bevy port's bug put every tap on MIP 0); every debug
// view written. The generic checks (presets validated, LP_NUM_THREADS, the stress suite, keys)
// are technique_coverage_test.cpp's and stress_test.cpp's.
#include <cmath>
#include <filesystem>
#include <set>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "gpu_test_support.h"
#include "xegtao/xegtao.h"

namespace aor::test {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

fs::path shipped(const std::string& name) { return fs::path(AOR_SOURCE_DIR) / "captures" / name; }

json readReport(const fs::path& out) { return json::parse(readText(out / "report.json")); }

TEST(XeGtaoNoise, HilbertIndexVisitsEveryTexelOfTheTileOnceAlongNeighbours) {
  std::vector<glm::ivec2> at(64 * 64, glm::ivec2(-1));
  for (uint32_t y = 0; y < 64; ++y)
    for (uint32_t x = 0; x < 64; ++x) {
      uint32_t index = shader::horizonHilbertIndex(x, y);
      ASSERT_LT(index, 64u * 64u);
      EXPECT_EQ(at[index], glm::ivec2(-1)) << x << "," << y << " shares index " << index;
      at[index] = glm::ivec2(x, y);
    }
  for (size_t i = 1; i < at.size(); ++i) {
    glm::ivec2 step = glm::abs(at[i] - at[i - 1]);
    EXPECT_EQ(step.x + step.y, 1) << "index " << i << " is not next to index " << i - 1;
  }
  // The curve tiles the screen: pixel (x + 64, y) takes the noise of (x, y).
  EXPECT_EQ(shader::horizonHilbertIndex(70, 3), shader::horizonHilbertIndex(6, 3));
}

TEST(XeGtaoNoise, FramesSixtyFourApartShareTheirNoiseAndNeighboursDoNot) {
  glm::vec2 a = shader::horizonNoise({5, 9}, 3), b = shader::horizonNoise({5, 9}, 3 + 64), c = shader::horizonNoise({5, 9}, 4);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  for (float v : {a.x, a.y, c.x, c.y}) {
    EXPECT_GE(v, 0.0f);
    EXPECT_LT(v, 1.0f);
  }
}

// Every depth format and denoise pass count of the issue, and the options that compile other code
// (bent normals, the thin-occluder falloff, the shared temporal pass), with validation on.
TEST(XeGtao, EveryDepthFormatDenoisePassCountAndOptionRunsValidationClean) {
  std::vector<std::string> variants;
  for (int depth32 : {0, 1})
    for (int passes : {1, 2, 3}) variants.push_back(fmt::format("--set depth32={} --set denoise_passes={}", depth32, passes));
  variants.push_back("--set bent=1 --set denoise_passes=2");
  variants.push_back("--set thin_occluder_compensation=0.5 --set temporal=0.9");
  variants.push_back("--set bent=1 --set temporal=0.9 --preset ultra");
  for (size_t i = 0; i < variants.size(); ++i) {
    fs::path out = scratchDir(fmt::format("xegtao-validate-{}", i)) / "out";
    auto r = runAoreplay(fmt::format("run {} --technique xegtao {} --frames 0:3 --validate --no-images --out {}",
                                     shipped("boxes-strafe").string(), variants[i], out.string()));
    EXPECT_EQ(r.exitCode, 0) << variants[i] << "\n" << r.output;
    EXPECT_NE(r.output.find("validation: 0 messages"), std::string::npos) << variants[i] << "\n" << r.output;
  }
}

TEST(XeGtao, ReplaysBitIdenticallyTwiceWithEveryOptionOn) {
  std::vector<std::string> settings{"bent=1", "depth32=1", "denoise_passes=3", "thin_occluder_compensation=0.3", "temporal=0.8"};
  auto first = replayWithSettings(shipped("boxes-strafe"), "xegtao", settings, 0, 4);
  auto second = replayWithSettings(shipped("boxes-strafe"), "xegtao", settings, 0, 4);
  ASSERT_EQ(first.frames.size(), 4u);
  ASSERT_EQ(second.frames.size(), 4u);
  for (size_t i = 0; i < first.frames.size(); ++i) {
    EXPECT_TRUE(bitIdentical(first.frames[i].visibility, second.frames[i].visibility)) << "frame " << i;
    EXPECT_TRUE(bitIdentical(first.frames[i].bent, second.frames[i].bent)) << "frame " << i;
    EXPECT_FALSE(first.frames[i].bent.empty());
  }
}

// The noise follows the capture's frame index (XeGTAO's NoiseIndex = frame % 64): a frame replayed
// alone is the same frame in a longer replay, and consecutive frames differ.
TEST(XeGtao, AFrameReplayedAloneEqualsItselfInALongerReplay) {
  auto all = replayWithSettings(shipped("boxes-static"), "xegtao", {}, 0, 4);
  auto alone = replayWithSettings(shipped("boxes-static"), "xegtao", {}, 2, 3);
  ASSERT_EQ(all.frames.size(), 4u);
  ASSERT_EQ(alone.frames.size(), 1u);
  EXPECT_TRUE(bitIdentical(all.frames[2].visibility, alone.frames[0].visibility));
  // boxes-static's camera does not move: only the noise tells frames 1 and 2 apart.
  EXPECT_FALSE(bitIdentical(all.frames[1].visibility, all.frames[2].visibility));
}

TEST(XeGtao, VisibilityIsInRangeAndSkyIsUnoccluded) {
  auto run = replayWithSettings(shipped("boxes-orbit"), "xegtao", {}, 0, 1);
  ASSERT_EQ(run.frames.size(), 1u);
  const auto& f = run.frames[0];
  double sum = 0;
  int below = 0;
  for (float v : f.visibility) {
    ASSERT_TRUE(std::isfinite(v));
    ASSERT_GE(v, 0.0f);
    ASSERT_LE(v, 1.0f);
    sum += v;
    below += v < 0.9f;
  }
  double mean = sum / double(f.visibility.size());
  EXPECT_GT(mean, 0.5);
  EXPECT_LT(mean, 0.99);
  EXPECT_GT(below, int(f.visibility.size() / 100)) << "a city block of boxes has creases";
  // The top-left pixel of boxes-orbit is sky.
  EXPECT_EQ(f.visibility[0], 1.0f);
}

// Seed 002's audit and the issue: ports that compute the MIP level in UV units sample MIP 0 only.
// At 1080p with the capture's radius XeGTAO's offsets reach 2^(3.3+1) pixels and beyond, so MIPs
// 1-4 must get taps; the counts add up to every tap of every pixel (sky included: XeGTAO samples
// there too).
TEST(XeGtao, MipTapsReachTheCoarseLevelsAt1080p) {
  auto capture = generatedCapture("boxes", "orbit", 1920, 1080, 1);
  fs::path out = scratchDir("xegtao-mip-taps") / "out";
  auto r = runAoreplay(fmt::format("run {} --technique xegtao --debug mip_taps --no-images --out {}", capture.string(),
                                   out.string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  json taps = readReport(out)["frames"][0]["debug"]["mip_taps"];
  ASSERT_EQ(taps.size(), 5u) << taps.dump();
  uint64_t total = 0, coarse = 0;
  for (size_t level = 0; level < 5; ++level) {
    total += taps[level].get<uint64_t>();
    if (level > 0) coarse += taps[level].get<uint64_t>();
  }
  std::cout << "mip_taps at 1920x1080 (xegtao high): " << taps.dump() << "\n";
  EXPECT_GT(coarse, 0u) << "every tap on MIP 0: " << taps.dump();
  EXPECT_GT(double(coarse), 0.05 * double(total)) << taps.dump();
  // high: 3 slices x 3 steps x 2 sides per pixel.
  EXPECT_EQ(total, 18ull * 1920 * 1080) << taps.dump();
}

TEST(XeGtao, EveryDebugViewIsWritten) {
  const Technique& t = findTechnique("xegtao");
  std::string views;
  for (const auto& v : t.debugViews) views += " --debug " + v.name;
  fs::path out = scratchDir("xegtao-debug") / "out";
  auto r = runAoreplay(fmt::format("run {} --technique xegtao --set bent=1 --frames 0:2{} --out {}",
                                   shipped("boxes-orbit").string(), views, out.string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const auto& v : t.debugViews) {
    if (v.name == "mip_taps") continue;
    for (const char* ext : {".exr", ".png"}) EXPECT_TRUE(fs::exists(out / "debug" / v.name / (std::string("0001") + ext))) << v.name << ext;
  }
  json report = readReport(out);
  EXPECT_EQ(report["frames"][1]["debug"]["mip_taps"].size(), 5u);
}

}  // namespace
}  // namespace aor::test
