// vbao (the visibility bitmask): its sector and weighting math on the CPU (the shader's own
// header), the check that needs no reference (an infinitely thick slab, cosine weights and no
// falloff or power is xegtao's horizon integral up to one sector a side) on every shipped capture,
// validation for every preset and weighting, bit-identity, every debug view. The generic checks
// (keys, stress suite, LP_NUM_THREADS) are technique_coverage_test.cpp's and stress_test.cpp's.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "capture/image_io.h"
#include "gpu_test_support.h"
#include "techniques/registry.h"
#include "vbao/vbao.h"

namespace aor::test {
namespace {

namespace fs = std::filesystem;
constexpr float kPi = shader::kVbaoPi;

fs::path shipped(const std::string& name) { return fs::path(AOR_SOURCE_DIR) / "captures" / name; }

std::vector<std::string> shippedCaptures() {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(fs::path(AOR_SOURCE_DIR) / "captures"))
    if (fs::exists(entry.path() / "capture.json")) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// What one sector of N weighs at most under cosine weights: the largest cumulative step over
// every sector of a fine sweep of normal angles n (the check's bound is one of these a side).
float largestSectorWeight(uint32_t sectors) {
  float largest = 0;
  for (int i = 0; i <= 180; ++i) {
    float n = -kPi / 2 + kPi * float(i) / 180.0f;
    for (uint32_t k = 0; k < sectors; ++k) {
      float a0 = n - kPi / 2 + kPi * float(k) / float(sectors), a1 = a0 + kPi / float(sectors);
      float w = shader::vbaoCosineCumulative(a1, n, std::cos(n), std::sin(n)) -
                shader::vbaoCosineCumulative(a0, n, std::cos(n), std::sin(n));
      largest = std::max(largest, w);
    }
  }
  return largest;
}

TEST(VbaoMath, SectorMaskCoversTheSpanFromFloorToCeiling) {
  EXPECT_EQ(shader::vbaoSectorMask(0.0f, 1.0f, 32), 0xffffffffu);
  EXPECT_EQ(shader::vbaoSectorMask(0.5f, 0.5f, 32), 0u) << "an empty span occupies nothing";
  EXPECT_EQ(shader::vbaoSectorMask(1.0f, 1.2f, 32), 0u) << "beyond the hemisphere";
  EXPECT_EQ(shader::vbaoSectorMask(-0.3f, 0.0f, 32), 0u);
  EXPECT_EQ(shader::vbaoSectorMask(0.26f, 0.27f, 32), 1u << 8) << "inside one sector: that sector";
  EXPECT_EQ(shader::vbaoSectorMask(0.24f, 0.51f, 8), 0xfu << 1) << "sectors 1..4 of 8";
  EXPECT_EQ(shader::vbaoSectorMask(0.9f, 2.0f, 4), 1u << 3);
}

TEST(VbaoMath, CosineWeightsAddUpToGtaosUnoccludedSlice) {
  for (float n : {-1.2f, -0.4f, 0.0f, 0.3f, 1.1f}) {
    float cosN = std::cos(n), sinN = std::sin(n), sum = 0;
    for (uint32_t k = 0; k < 32; ++k) {
      float a0 = n - kPi / 2 + kPi * float(k) / 32.0f, a1 = a0 + kPi / 32.0f;
      float w = shader::vbaoCosineCumulative(a1, n, cosN, sinN) - shader::vbaoCosineCumulative(a0, n, cosN, sinN);
      EXPECT_GE(w, -1e-6f) << "n " << n << " sector " << k;
      sum += w;
    }
    // GTAO's iarc0 + iarc1 with the horizons at the hemisphere's edges.
    auto iarc = [&](float h) { return (cosN + 2.0f * h * sinN - std::cos(2.0f * h - n)) / 4.0f; };
    EXPECT_NEAR(sum, iarc(n - kPi / 2) + iarc(n + kPi / 2), 1e-5f) << "n " << n;
  }
  EXPECT_NEAR(largestSectorWeight(32), 0.098f, 0.002f);  // pi/32 at grazing normals
}

struct RawTerms {
  std::vector<float> visibility;  // the main pass's visibility, from its 8-bit working term
};

RawTerms rawVisibility(const std::string& capture, const std::string& technique, const std::string& sets,
                       const std::string& folder) {
  fs::path out = scratchDir(folder) / "out";
  auto r = runAoreplay(fmt::format("run {} --technique {} {} --frames 0:1 --debug ao_raw --out {}", shipped(capture).string(),
                                   technique, sets, out.string()));
  EXPECT_EQ(r.exitCode, 0) << r.output;
  auto channels = readExrChannels(out / "debug" / "ao_raw" / "0000.exr", {"R"});
  RawTerms t;
  for (float stored : channels.at("R")) t.visibility.push_back(stored * shader::kHorizonOcclusionTermScale / 255.0f);
  return t;
}

// Issue 50's consistency check: with an infinitely thick slab every sample occludes everything
// beyond its front angle, which is the horizon; cosine weights integrate GTAO's arc over the open
// sectors. vbao opens only whole sectors, so it sees at most what xegtao sees and at least that
// minus one sector's weight a side (plus one 8-bit step of the working term each).
TEST(Vbao, InfiniteThicknessCosineEqualsXegtaoWithinOneSectorASideOnEveryShippedCapture) {
  const float bound = 2.0f * largestSectorWeight(32), step = shader::kHorizonOcclusionTermScale / 255.0f;
  for (const auto& capture : shippedCaptures()) {
    auto xe = rawVisibility(capture, "xegtao", "--set falloff_range=0 --set final_value_power=1", "vbao-check-xe-" + capture);
    auto vb = rawVisibility(capture, "vbao",
                            "--set thickness=1e6 --set weighting=cosine --set falloff_range=0 --set final_value_power=1",
                            "vbao-check-vb-" + capture);
    ASSERT_EQ(xe.visibility.size(), vb.visibility.size()) << capture;
    ASSERT_FALSE(xe.visibility.empty()) << capture;
    double sum = 0, largest = 0;
    size_t above = 0, beyond = 0;
    for (size_t i = 0; i < xe.visibility.size(); ++i) {
      double d = double(xe.visibility[i]) - double(vb.visibility[i]);
      sum += std::abs(d);
      largest = std::max(largest, d);
      above += d < -1.01 * step;
      beyond += d > bound + 1.01 * step;
    }
    double mean = sum / double(xe.visibility.size());
    std::cout << fmt::format("{}: xegtao - vbao mean |d| {:.4f}, largest {:.4f} (bound {:.4f} + one step {:.4f})\n", capture,
                             mean, largest, bound, step);
    EXPECT_EQ(above, 0u) << capture << ": vbao brighter than xegtao by more than one 8-bit step";
    EXPECT_EQ(beyond, 0u) << capture << ": vbao darker than xegtao by more than one sector a side";
    // On average a side loses about half a sector, mostly far less than the grazing worst case.
    EXPECT_LT(mean, 0.125 * bound) << capture;
  }
}

TEST(Vbao, EveryPresetAndWeightingRunsValidationClean) {
  std::vector<std::string> variants;
  for (const char* preset : {"low", "medium", "high", "ultra"})
    for (const char* weighting : {"uniform", "cosine"})
      variants.push_back(fmt::format("--preset {} --set weighting={}", preset, weighting));
  variants.push_back("--set depth32=1 --set denoise_passes=3 --set sectors=7 --set temporal=0.9 --debug sectors");
  variants.push_back("--set sectors=0 --set weighting=uniform --preset ultra");
  for (size_t i = 0; i < variants.size(); ++i) {
    fs::path out = scratchDir(fmt::format("vbao-validate-{}", i)) / "out";
    auto r = runAoreplay(fmt::format("run {} --technique vbao {} --frames 0:3 --validate --no-images --out {}",
                                     shipped("boxes-strafe").string(), variants[i], out.string()));
    EXPECT_EQ(r.exitCode, 0) << variants[i] << "\n" << r.output;
    EXPECT_NE(r.output.find("validation: 0 messages"), std::string::npos) << variants[i] << "\n" << r.output;
  }
}

TEST(Vbao, ReplaysBitIdenticallyTwice) {
  for (const char* weighting : {"weighting=uniform", "weighting=cosine"}) {
    std::vector<std::string> settings{weighting, "depth32=1", "denoise_passes=2", "thickness=0.1", "temporal=0.8"};
    auto first = replayWithSettings(shipped("thin-strafe"), "vbao", settings, 0, 4);
    auto second = replayWithSettings(shipped("thin-strafe"), "vbao", settings, 0, 4);
    ASSERT_EQ(first.frames.size(), 4u);
    ASSERT_EQ(second.frames.size(), 4u);
    for (size_t i = 0; i < first.frames.size(); ++i)
      EXPECT_TRUE(bitIdentical(first.frames[i].visibility, second.frames[i].visibility)) << weighting << " frame " << i;
  }
}

// What the slab does: thinner slabs let light pass behind thin occluders, so mean visibility grows
// as thickness shrinks; the weighting changes the answer.
TEST(Vbao, ThinnerSlabsOccludeLessAndTheWeightingMatters) {
  auto meanOf = [](const std::vector<std::string>& settings) {
    auto run = replayWithSettings(shipped("thin-depth2"), "vbao", settings, 0, 1);
    double sum = 0;
    for (float v : run.frames.at(0).visibility) sum += v;
    return sum / double(run.frames.at(0).visibility.size());
  };
  double thin = meanOf({"thickness=0.05"}), medium = meanOf({"thickness=0.25"}), thick = meanOf({"thickness=1e6"});
  std::cout << fmt::format("thin-depth2 mean visibility: thickness 0.05 {:.4f}, 0.25 {:.4f}, 1e6 {:.4f}\n", thin, medium, thick);
  EXPECT_GT(thin, medium);
  EXPECT_GT(medium, thick);
  EXPECT_NE(meanOf({"weighting=uniform"}), medium);
}

struct HaloBand {
  double rmse = 0, bias = 0;
};

HaloBand haloBandAtDefaults(const std::string& technique) {
  fs::path out = scratchDir("vbao-halo-" + technique) / "out";
  auto r = runAoreplay(fmt::format("run {} --technique {} --no-images --out {}", shipped("thin-depth2").string(), technique,
                                   out.string()));
  EXPECT_EQ(r.exitCode, 0) << r.output;
  auto band = nlohmann::json::parse(readText(out / "report.json"))["metrics"]["error"]["halo_band"];
  return {band["rmse"].get<double>(), band["bias"].get<double>()};
}

// Issue 50: the measured ordering on thin-depth2 at every technique's defaults. vbao has the
// lowest halo-band RMSE of the three and a smaller |bias| than gtao; xegtao's |bias| is smaller
// than vbao's, not larger as the paper's claim would have it (replay/techniques/vbao/README.md,
// "Thin occluders": every technique here is too bright in this band at power 1, and xegtao's
// default power 2.2 darkens it).
TEST(Vbao, HaloBandOnThinOccludersAgainstGtaoAndXegtao) {
  HaloBand vbao = haloBandAtDefaults("vbao"), gtao = haloBandAtDefaults("gtao"), xegtao = haloBandAtDefaults("xegtao");
  std::cout << fmt::format("thin-depth2 halo band RMSE / bias: vbao {:.4f} / {:+.4f}, gtao {:.4f} / {:+.4f}, xegtao {:.4f} / {:+.4f}\n",
                           vbao.rmse, vbao.bias, gtao.rmse, gtao.bias, xegtao.rmse, xegtao.bias);
  EXPECT_LT(vbao.rmse, gtao.rmse);
  EXPECT_LT(vbao.rmse, xegtao.rmse);
  EXPECT_LT(std::abs(vbao.bias), std::abs(gtao.bias));
  EXPECT_LT(std::abs(xegtao.bias), std::abs(vbao.bias));
}

TEST(Vbao, EveryDebugViewIsWritten) {
  const Technique& t = findTechnique("vbao");
  std::string views;
  for (const auto& v : t.debugViews) views += " --debug " + v.name;
  fs::path out = scratchDir("vbao-debug") / "out";
  auto r = runAoreplay(fmt::format("run {} --technique vbao --frames 0:2{} --out {}", shipped("boxes-orbit").string(), views,
                                   out.string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const auto& v : t.debugViews)
    for (const char* ext : {".exr", ".png"})
      EXPECT_TRUE(fs::exists(out / "debug" / v.name / (std::string("0001") + ext))) << v.name << ext;
  // The share of sectors occupied lies in [0, 1] and is not 0 everywhere on a scene of boxes.
  auto sectors = readExrChannels(out / "debug" / "sectors" / "0001.exr", {"R"}).at("R");
  EXPECT_GE(*std::min_element(sectors.begin(), sectors.end()), 0.0f);
  EXPECT_LE(*std::max_element(sectors.begin(), sectors.end()), 1.0f);
  EXPECT_GT(*std::max_element(sectors.begin(), sectors.end()), 0.1f);
}

}  // namespace
}  // namespace aor::test
