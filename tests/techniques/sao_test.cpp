// SAO (seed 004) and its second layer: the second-layer path exists only where the capture has a
// second layer (nothing declared otherwise, dual_layer=1 refused with exit 2), both paths validate
// clean and replay bit-identically, and on the shipped thin-occluder capture the second layer
// lowers the error behind the occluders' silhouettes (the halo band) against the ray-traced
// reference. The figures it prints are the ones in replay/techniques/sao/README.md.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "shared_passes/camera.h"
#include "capture/image_io.h"
#include "gpu_test_support.h"
#include "metrics/depth.h"
#include "metrics/error_metrics.h"
#include "metrics/halo_band.h"

namespace aor::test {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

fs::path thinDepth2() { return fs::path(AOR_SOURCE_DIR) / "captures" / "thin-depth2"; }

json reportOf(const fs::path& out) { return json::parse(readText(out / "report.json")); }

const json* resourceNamed(const json& report, const std::string& name) {
  for (const auto& r : report["memory"]["resources"])
    if (r["name"] == name) return &r;
  return nullptr;
}

TEST(Sao, WithoutASecondLayerNothingOfOneIsDeclared) {
  auto capture = generatedCapture("thin", "strafe", 64, 36, 2);
  ASSERT_FALSE(loadCapture(capture).hasDepth2);
  fs::path out = scratchDir("sao-single") / "out";
  auto r = runAoreplay(fmt::format("run {} --technique sao --validate --no-images --out {}", capture.string(), out.string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("validation: 0 messages"), std::string::npos) << r.output;
  json report = reportOf(out);
  EXPECT_EQ(resourceNamed(report, "depth2"), nullptr) << report["memory"].dump(1);
  const json* csz = resourceNamed(report, "csz");
  ASSERT_NE(csz, nullptr);
  EXPECT_EQ((*csz)["format"], "R16_SFLOAT");
  EXPECT_EQ((*csz)["mip_levels"], 5);
  // Forcing the single-layer path on such a capture changes nothing, not even the peak memory.
  fs::path forced = scratchDir("sao-single-forced") / "out";
  r = runAoreplay(fmt::format("run {} --technique sao --set dual_layer=0 --no-images --out {}", capture.string(), forced.string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(reportOf(forced)["memory"]["peak_gpu_bytes"], report["memory"]["peak_gpu_bytes"]);
  // And the graph command shows no second layer either.
  r = runAoreplay(fmt::format("graph {} --technique sao --dot {}", capture.string(),
                              (scratchDir("sao-single-graph") / "graph.dot").string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(r.output.find("depth2"), std::string::npos) << r.output;
}

TEST(Sao, ADepthOnlyCaptureUsesTheFrontsReconstructedNormals) {
  auto capture = generatedCapture("thin", "strafe", 64, 36, 2, /*normals=*/false);
  fs::path out = scratchDir("sao-depth-only") / "out";
  auto r = runAoreplay(fmt::format("run {} --technique sao --validate --no-images --out {}", capture.string(), out.string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("validation: 0 messages"), std::string::npos) << r.output;
  json report = reportOf(out);
  const json* normals = resourceNamed(report, "normals_reconstructed");
  ASSERT_NE(normals, nullptr);
  EXPECT_EQ((*normals)["allocated"], true);
}

TEST(Sao, DualLayerOnACaptureWithoutOneExitsTwoNamingIt) {
  auto capture = generatedCapture("thin", "strafe", 64, 36, 2);
  fs::path out = scratchDir("sao-dual-refused") / "out";
  auto r = runAoreplay(fmt::format("run {} --technique sao --set dual_layer=1 --out {}", capture.string(), out.string()));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("dual_layer"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("depth2"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out / "report.json"));
}

TEST(Depth2Capture, TheSeparationIsCheckedAndNeedsTheSecondLayer) {
  fs::path out = scratchDir("depth2-cli") / "capture";
  auto r = runAoreplay(fmt::format("capture thin --size 32x18 --frames 1 --depth2-separation 0.05 --out {}", out.string()));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("--depth2-separation"), std::string::npos) << r.output;
  r = runAoreplay(fmt::format("capture thin --size 32x18 --frames 1 --depth2 --depth2-separation 0 --out {}", out.string()));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("depth2_separation"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
  r = runAoreplay(fmt::format("capture thin --size 32x18 --frames 1 --depth2 --out {}", out.string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_TRUE(loadCapture(out).hasDepth2);
}

TEST(Sao, TheShippedThinCaptureRunsBothPathsValidationClean) {
  for (const char* dual : {"0", "1"}) {
    fs::path out = scratchDir(fmt::format("sao-validate-{}", dual)) / "out";
    auto r = runAoreplay(fmt::format("run {} --technique sao --set dual_layer={} --validate --no-images --out {}",
                                     thinDepth2().string(), dual, out.string()));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("validation: 0 messages"), std::string::npos) << r.output;
    json report = reportOf(out);
    const json* csz = resourceNamed(report, "csz");
    ASSERT_NE(csz, nullptr);
    EXPECT_EQ((*csz)["format"], std::string(dual) == "1" ? "R16G16_SFLOAT" : "R16_SFLOAT");
    const json* depth2 = resourceNamed(report, "depth2");
    // The capture's second layer is declared by the front, allocated only when a pass reads it.
    ASSERT_NE(depth2, nullptr);
    EXPECT_EQ((*depth2)["allocated"], std::string(dual) == "1");
  }
  fs::path out = scratchDir("sao-csz32") / "out";
  auto r = runAoreplay(fmt::format("run {} --technique sao --set csz32=1 --validate --no-images --out {}",
                                   thinDepth2().string(), out.string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("validation: 0 messages"), std::string::npos) << r.output;
  EXPECT_EQ((*resourceNamed(reportOf(out), "csz"))["format"], "R32G32_SFLOAT");
  // With the shared temporal block after the blur: frame 1 blends frame 0's history.
  out = scratchDir("sao-temporal") / "out";
  r = runAoreplay(fmt::format("run {} --technique sao --set temporal=0.5 --validate --no-images --out {}",
                              thinDepth2().string(), out.string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("validation: 0 messages"), std::string::npos) << r.output;
  EXPECT_EQ(reportOf(out)["frames"][1]["history"], "valid");
}

TEST(Sao, DualLayerOutputsAreBitIdenticalWhateverTheLavapipeThreadCount) {
  auto runWith = [&](int threads) {
    fs::path out = scratchDir(fmt::format("sao-threads-{}", threads)) / "out";
    auto r = runAoreplay(fmt::format("run {} --technique sao --set dual_layer=1 --out {}", thinDepth2().string(), out.string()),
                         fmt::format("LP_NUM_THREADS={}", threads));
    EXPECT_EQ(r.exitCode, 0) << r.output;
    return out;
  };
  fs::path one = runWith(1), four = runWith(4);
  for (const char* frame : {"0000.exr", "0001.exr"})
    EXPECT_EQ(readText(one / "ao" / frame), readText(four / "ao" / frame)) << frame;
}

TEST(Sao, BothPathsReplayBitIdenticallyTwiceAndDiffer) {
  std::vector<float> outputs[2];
  for (int dual = 0; dual < 2; ++dual) {
    auto a = replayWithSettings(thinDepth2(), "sao", {fmt::format("dual_layer={}", dual)});
    auto b = replayWithSettings(thinDepth2(), "sao", {fmt::format("dual_layer={}", dual)});
    ASSERT_EQ(a.frames.size(), b.frames.size());
    for (size_t i = 0; i < a.frames.size(); ++i) EXPECT_TRUE(bitIdentical(a.frames[i].visibility, b.frames[i].visibility)) << i;
    outputs[dual] = a.frames.at(0).visibility;
  }
  EXPECT_FALSE(bitIdentical(outputs[0], outputs[1])) << "the second layer changed nothing";
}

// The radius's whole range gives finite visibility in [0, 1]: the estimator forms no power of it.
TEST(Sao, ExtremeRadiiStayFiniteAndBounded) {
  for (const char* radius : {"radius=1e-06", "radius=10000000"}) {
    auto run = replayWithSettings(thinDepth2(), "sao", {radius, "dual_layer=1"}, 0, 1);
    for (float v : run.frames.at(0).visibility) {
      ASSERT_TRUE(std::isfinite(v)) << radius;
      ASSERT_GE(v, 0.0f) << radius;
      ASSERT_LE(v, 1.0f) << radius;
    }
  }
}

// The seed's steps as debug views: both layers' camera-space Z, the pyramid's levels at their
// sizes, and the AO before, between and after the blur legs.
TEST(Sao, DebugViewsShowEveryStep) {
  fs::path out = scratchDir("sao-debug") / "out";
  std::string views;
  for (const char* v : {"csz", "csz_mip1", "csz_mip2", "csz_mip3", "csz_mip4", "ao_raw", "ao_blur_h", "ao"})
    views += fmt::format(" --debug {}", v);
  auto r = runAoreplay(fmt::format("run {} --technique sao --frames 0:1{} --out {}", thinDepth2().string(), views, out.string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  auto csz = readExrHeader(out / "debug" / "csz" / "0000.exr");
  EXPECT_EQ(csz.width, 320);
  EXPECT_EQ(csz.channels.size(), 2u) << "layer 0 and layer 1";
  for (int level = 1; level <= 4; ++level) {
    auto mip = readExrHeader(out / "debug" / fmt::format("csz_mip{}", level) / "0000.exr");
    EXPECT_EQ(mip.width, 320 >> level);
    EXPECT_EQ(mip.height, 180 >> level);
  }
  // Rotated-grid subsampling keeps real depths: level 1's texel (0, 0) is level 0's (1, 1).
  auto level0 = readExrChannels(out / "debug" / "csz" / "0000.exr", {csz.channels.begin()->first});
  auto level1 = readExrChannels(out / "debug" / "csz_mip1" / "0000.exr", {csz.channels.begin()->first});
  EXPECT_EQ(level1.begin()->second.at(0), level0.begin()->second.at(1 * 320 + 1));
  // Each blur leg smooths: the raw AO varies most between neighbours.
  auto roughness = [&](const char* view) {
    auto header = readExrHeader(out / "debug" / view / "0000.exr");
    auto plane = readExrChannels(out / "debug" / view / "0000.exr", {header.channels.begin()->first}).begin()->second;
    double sum = 0;
    for (int y = 0; y < 180; ++y)
      for (int x = 1; x < 320; ++x) sum += std::abs(plane[y * 320 + x] - plane[y * 320 + x - 1]);
    return sum;
  };
  EXPECT_GT(roughness("ao_raw"), roughness("ao_blur_h"));
  EXPECT_GT(roughness("ao_blur_h"), roughness("ao"));
}

struct HaloFigures {
  int64_t pixels = 0, bandPixels = 0;
  double rmse[2] = {0, 0}, bandRmse[2] = {0, 0}, bandBias[2] = {0, 0};  // [single, dual]
};

// Side by side: single layer, dual layer, reference.
void writeSideBySide(const fs::path& png, int w, int h, const float* single, const float* dual, const float* reference) {
  std::vector<float> side(size_t(3 * w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      size_t i = size_t(y) * w + x, row = size_t(y) * 3 * w;
      side[row + x] = single[i];
      side[row + w + x] = dual[i];
      side[row + 2 * w + x] = reference[i];
    }
  writePngGray(png, 3 * w, h, side.data());
}

// With AOR_SAO_FIGURES=DIR, the README's pictures of frame 0: single, dual and reference side by
// side, and the band.
void writeHaloFigures(const std::string& name, const fs::path& path) {
  const char* dir = std::getenv("AOR_SAO_FIGURES");
  if (!dir) return;
  Capture capture = loadCapture(path);
  ReplayedFrames runs[2] = {replayWithSettings(path, "sao", {"dual_layer=0"}, 0, 1),
                            replayWithSettings(path, "sao", {"dual_layer=1"}, 0, 1)};
  auto reference = loadReference(capture, 0);
  ASSERT_TRUE(reference.has_value());
  writeSideBySide(fs::path(dir) / (name + "_single_dual_reference.png"), capture.width, capture.height,
                  runs[0].frames[0].visibility.data(), runs[1].frames[0].visibility.data(), reference->data());
  const GBuffer g = loadGBuffer(capture, 0);
  HaloBandOptions options;
  options.radius = float(*captureRadius(capture));
  options.pixelsPerUnit = projectionParams(capture.frames[0].projection, capture.width, capture.height).pixelsPerUnit;
  auto band = haloBandMask(linearViewDistances(g.depth, capture.frames[0].projection), capture.width, capture.height, options);
  std::vector<float> bandImage(band.begin(), band.end());
  writePngGray(fs::path(dir) / (name + "_halo_band.png"), capture.width, capture.height, bandImage.data());
}

// Error in the halo band and overall, single against dual layer, as `aoreplay run` reports them
// (report.json's metrics.error and metrics.error.halo_band); the band is the same pixels for both
// (it depends on layer 0 and the capture's radius only).
HaloFigures measureHalo(const std::string& name) {
  fs::path path = fs::path(AOR_SOURCE_DIR) / "captures" / name;
  HaloFigures out;
  for (int dual = 0; dual < 2; ++dual) {
    const fs::path run = scratchDir(fmt::format("sao-halo-{}-{}", name, dual));
    const auto r = runAoreplay(fmt::format("run {} --technique sao --set dual_layer={} --no-images --out {}", path.string(),
                                           dual, (run / "out").string()));
    EXPECT_EQ(r.exitCode, 0) << r.output;
    if (r.exitCode != 0) return out;
    const nlohmann::json error = nlohmann::json::parse(readText(run / "out" / "report.json"))["metrics"]["error"];
    const nlohmann::json& band = error["halo_band"];
    EXPECT_EQ(band["radius"].get<double>(), *captureRadius(loadCapture(path))) << "the band uses the capture's radius";
    if (dual == 0) out.pixels = error["pixels"].get<int64_t>(), out.bandPixels = band["pixels"].get<int64_t>();
    EXPECT_EQ(band["pixels"].get<int64_t>(), out.bandPixels) << "the same band for both layers";
    out.rmse[dual] = error["rmse"].get<double>();
    out.bandRmse[dual] = band["rmse"].get<double>();
    out.bandBias[dual] = band["bias"].get<double>();
  }
  writeHaloFigures(name, path);
  std::printf("%s: halo band %lld of %lld surface pixels\n", name.c_str(), (long long)out.bandPixels,
              (long long)out.pixels);
  for (int dual = 0; dual < 2; ++dual)
    std::printf("  %s layer: RMSE %.4f, halo-band RMSE %.4f, halo-band bias %+.4f\n", dual ? "dual  " : "single",
                out.rmse[dual], out.bandRmse[dual], out.bandBias[dual]);
  return out;
}

TEST(Sao, TheSecondLayerLowersTheHaloErrorBehindThinOccluders) {
  // The papers' 1 cm separation: behind a 4 cm pole the second layer is mostly its back face.
  HaloFigures oneCm = measureHalo("thin-depth2");
  ASSERT_GT(oneCm.bandPixels, 1000) << "the band must cover a real part of the image";
  EXPECT_LT(oneCm.bandRmse[1], oneCm.bandRmse[0]);
  EXPECT_LT(oneCm.bandBias[1], oneCm.bandBias[0]) << "single layer misses occlusion behind silhouettes: too open";
  // 5 cm, thicker than the poles and slats: the second layer is what they hide; the whole image gains.
  HaloFigures fiveCm = measureHalo("thin-depth2-5cm");
  EXPECT_LT(fiveCm.bandRmse[1], fiveCm.bandRmse[0]);
  EXPECT_LT(fiveCm.rmse[1], fiveCm.rmse[0]);
  EXPECT_LT(fiveCm.bandRmse[1], oneCm.bandRmse[1]);
}

}  // namespace
}  // namespace aor::test
