// Seed 003's ray-traced AO (--technique rtao): bad input (no geometry, a bad OBJ) exits 2 naming
// it, a replay validates clean and is bit-identical twice, and the accumulation follows the seed's
// updateFrame/resetFrame exactly: it restarts on the frame the camera moves, and on that frame
// equals the same frame replayed alone. The ray-query path, on a device with ray queries, gives
// the compute path's image within the tolerance of replay/techniques/rtao/README.md.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "gpu_test_support.h"

namespace aor::test {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

json reportOf(const fs::path& out) { return json::parse(readText(out / "report.json")); }

std::vector<double> accumulatedFrames(const json& report) {
  std::vector<double> frames;
  for (const auto& f : report["frames"]) frames.push_back(f["technique"]["accumulated_frames"].get<double>());
  return frames;
}

// A private copy of a generated capture, to edit.
fs::path copyOf(const fs::path& capture, const std::string& name) {
  fs::path dir = scratchDir(name + "-capture") / "capture";
  fs::copy(capture, dir, fs::copy_options::recursive);
  return dir;
}

TEST(Rtao, ACaptureWithoutGeometryExitsTwoSayingSo) {
  fs::path capture = planeCapture("rtao-no-geometry", {});
  ASSERT_FALSE(loadCapture(capture).geometry);
  fs::path out = scratchDir("rtao-no-geometry") / "out";
  auto r = runAoreplay(fmt::format("run {} --technique rtao --out {}", capture.string(), out.string()));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("capture.json: field \"geometry\": --technique rtao traces rays"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out / "report.json"));
}

TEST(Rtao, ABadObjExitsTwoNamingItsLine) {
  fs::path capture = copyOf(generatedCapture("boxes", "static", 32, 18, 1), "rtao-bad-obj");
  std::string text = readText(capture / "scene.obj");
  // Line 3 is the second vertex (line 1 is the comment).
  size_t second = text.find('\n', text.find('\n') + 1) + 1;
  text.replace(second, text.find('\n', second) - second, "v 1 nan 2");
  std::ofstream(capture / "scene.obj", std::ios::binary | std::ios::trunc) << text;
  fs::path out = scratchDir("rtao-bad-obj") / "out";
  auto r = runAoreplay(fmt::format("run {} --technique rtao --out {}", capture.string(), out.string()));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("scene.obj: line 3: vertex coordinate y = nan is not a finite 32-bit float"), std::string::npos)
      << r.output;
}

// The ray-query extensions the default device lacks, comma-separated; empty when it has both.
std::string missingRayQuery() {
  std::vector<std::string> missing;
  for (const char* e : {kRayQueryExtension, kAccelerationStructureExtension})
    if (!validatedContext().info.hasExtension(e)) missing.push_back(e);
  return fmt::format("{}", fmt::join(missing, ", "));
}

std::string skipReason(const std::string& missing) {
  return fmt::format("device '{}' lacks {}, so the ray-query path cannot run here (bookworm-backports' lavapipe has "
                     "them: replay/techniques/rtao/README.md)", validatedContext().info.name, missing);
}

TEST(Rtao, RayQueryOnADeviceWithoutItExitsThreeNamingTheExtension) {
  if (missingRayQuery().empty())
    GTEST_SKIP() << "device '" << validatedContext().info.name << "' has VK_KHR_ray_query and VK_KHR_acceleration_structure";
  fs::path capture = generatedCapture("boxes", "static", 32, 18, 1);
  fs::path out = scratchDir("rtao-rayquery") / "out";
  auto r = runAoreplay(fmt::format("run {} --technique rtao --set traversal=rayquery --out {}", capture.string(), out.string()));
  EXPECT_EQ(r.exitCode, 3) << r.output;
  EXPECT_NE(r.output.find("needs " + missingRayQuery() + ", which device"), std::string::npos) << r.output;
}

TEST(Rtao, ValidatesCleanAndIsBitIdenticalTwice) {
  fs::path capture = generatedCapture("boxes", "static", 64, 36, 3);
  std::vector<fs::path> outs;
  for (int run = 0; run < 2; ++run) {
    outs.push_back(scratchDir(fmt::format("rtao-twice-{}", run)) / "out");
    auto r = runAoreplay(fmt::format("run {} --technique rtao --set traversal=compute --validate --out {}", capture.string(),
                                     outs.back().string()));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("validation: 0 messages"), std::string::npos) << r.output;
  }
  for (int frame = 0; frame < 3; ++frame) {
    std::string name = fmt::format("ao/{:04}.exr", frame);
    EXPECT_EQ(readText(outs[0] / name), readText(outs[1] / name)) << name;
  }
  json report = reportOf(outs[0]);
  EXPECT_EQ(accumulatedFrames(report), (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(report["frames"][2]["technique"]["accumulated_spp"], 12.0);  // samples 4 x 3 frames
  const json& bvh = report["technique_state"];
  EXPECT_EQ(bvh["rayquery"], 0.0) << bvh.dump();
  EXPECT_GT(bvh["bvh_triangles"].get<double>(), 100.0) << bvh.dump();
  EXPECT_EQ(bvh["bvh_bytes"].get<double>(), bvh["bvh_nodes"].get<double>() * 32 + bvh["bvh_triangles"].get<double>() * 48);
  EXPECT_GE(report["setup_ms"].get<double>(), bvh["bvh_build_ms"].get<double>());
  EXPECT_TRUE(report["gpu_ms_total_median"].is_number());
}

// The camera moves once (a centimetre, far below the host's jump limits) in a still capture: the
// accumulation restarts exactly there, and that frame equals the frame replayed on its own.
TEST(Rtao, AccumulationRestartsExactlyOnACameraMove) {
  fs::path capture = copyOf(generatedCapture("boxes", "static", 48, 27, 6), "rtao-move");
  json doc = json::parse(readText(capture / "capture.json"));
  for (int frame = 3; frame < 6; ++frame) doc["frames"][frame]["view"][12] = doc["frames"][frame]["view"][12].get<double>() + 0.01;
  std::ofstream(capture / "capture.json", std::ios::binary | std::ios::trunc) << doc.dump(2);
  fs::path out = scratchDir("rtao-move") / "out";
  auto r = runAoreplay(fmt::format("run {} --technique rtao --out {}", capture.string(), out.string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  json report = reportOf(out);
  EXPECT_EQ(accumulatedFrames(report), (std::vector<double>{1, 2, 3, 1, 2, 3}));
  EXPECT_EQ(report["frames"][3]["history"], "valid") << "the host's rules keep history: the move is the seed's reset";
  fs::path alone = scratchDir("rtao-move-alone") / "out";
  r = runAoreplay(fmt::format("run {} --technique rtao --frames 3:5 --out {}", capture.string(), alone.string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(readText(out / "ao/0003.exr"), readText(alone / "ao/0003.exr"));
  EXPECT_EQ(readText(out / "ao/0004.exr"), readText(alone / "ao/0004.exr"));
  EXPECT_NE(readText(out / "ao/0003.exr"), readText(out / "ao/0004.exr"));
}

// `aoreplay graph` compiles a steady-state frame (the second, reading the first's mean) without a device.
TEST(Rtao, GraphShowsTheTraceReadingLastFramesMean) {
  fs::path capture = generatedCapture("boxes", "static", 32, 18, 2);
  auto r = runAoreplay(fmt::format("graph {} --technique rtao --dot {}", capture.string(),
                                   (scratchDir("rtao-graph") / "graph.dot").string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("rtao_mean.previous"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("bvh_nodes"), std::string::npos) << r.output;
}

TEST(Rtao, AccumulateOffAndMaxFrames) {
  fs::path capture = generatedCapture("boxes", "static", 48, 27, 4);
  fs::path off = scratchDir("rtao-off") / "out";
  auto r = runAoreplay(fmt::format("run {} --technique rtao --set accumulate=0 --no-images --out {}", capture.string(), off.string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(accumulatedFrames(reportOf(off)), (std::vector<double>{1, 1, 1, 1}));
  fs::path capped = scratchDir("rtao-capped") / "out";
  r = runAoreplay(fmt::format("run {} --technique rtao --set max_frames=2 --out {}", capture.string(), capped.string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(accumulatedFrames(reportOf(capped)), (std::vector<double>{1, 2, 2, 2}));
  EXPECT_EQ(readText(capped / "ao/0001.exr"), readText(capped / "ao/0003.exr")) << "a capped mean is kept as it is";
}

// Error against the capture's Embree reference falls with the accumulated samples (the convergence
// of replay/techniques/rtao/README.md, small): 16 spp in one frame, then 64 after four.
TEST(Rtao, AccumulationConvergesToTheReference) {
  fs::path capture = fs::path(AOR_SOURCE_DIR) / "captures" / "boxes-static";
  fs::path out = scratchDir("rtao-converge") / "out";
  auto r = runAoreplay(fmt::format("run {} --technique rtao --set distance_based=0 --set power=1 --set samples=16 --frames 0:4 "
                                   "--no-images --out {}",
                                   capture.string(), out.string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  json report = reportOf(out);
  double first = report["frames"][0]["metrics"]["error"]["rmse"].get<double>();
  double last = report["frames"][3]["metrics"]["error"]["rmse"].get<double>();
  std::printf("rtao boxes-static 160x90: RMSE %.4f at 16 spp, %.4f at 64 spp\n", first, last);
  EXPECT_LT(last, first * 0.75);
}

// `aoreplay graph` with traversal=rayquery: the trace reads the TLAS as an acceleration structure.
TEST(Rtao, GraphShowsTheRayQueryTraceReadingTheTlas) {
  fs::path capture = generatedCapture("boxes", "static", 32, 18, 2);
  auto r = runAoreplay(fmt::format("graph {} --technique rtao --set traversal=rayquery --dot {}", capture.string(),
                                   (scratchDir("rtao-graph-rq") / "graph.dot").string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("rtao_tlas (acceleration structure read)"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("bvh_nodes"), std::string::npos) << r.output;
}

// A context validated as the shared one (synchronization included), with the ray-query extensions.
ContextOptions rayQueryContext() {
  ContextOptions options{"", true};
  options.optionalExtensions = [](const DeviceInfo&) {
    return std::vector<std::string>{kRayQueryExtension, kAccelerationStructureExtension};
  };
  return options;
}

std::vector<std::vector<float>> replayedVisibility(VulkanContext& vk, const Capture& capture,
                                                   const std::vector<std::string>& assignments) {
  ReplayOptions options(resolveSettings(findTechnique("rtao"), capture, "", assignments));
  std::vector<std::vector<float>> frames;
  replayCapture(vk, capture, options, [&](const FrameOutput& f) { frames.push_back(f.visibility); });
  return frames;
}

// The tolerance of the README ("The two paths"): a pixel differs visibly beyond kPixelTolerance;
// at most kDifferingFraction of all pixels of all frames may, and the mean |difference| is at most
// kMeanTolerance.
constexpr double kPixelTolerance = 1e-3, kDifferingFraction = 1e-4, kMeanTolerance = 1e-5;

// |compute - rayquery| per pixel over every frame of two replays.
struct PathDifference {
  double max = 0, mean = 0, meanVisibility = 0;
  size_t pixels = 0, differing = 0, beyond = 0;  // all; |d| > 0; |d| > kPixelTolerance
  size_t computeBrighter = 0;                    // of `beyond`: the compute path's rays found less occlusion
};

PathDifference differenceOf(const std::vector<std::vector<float>>& a, const std::vector<std::vector<float>>& b) {
  PathDifference d;
  for (size_t f = 0; f < a.size(); ++f)
    for (size_t i = 0; i < a[f].size(); ++i) {
      double diff = std::abs(double(a[f][i]) - double(b[f][i]));
      d.max = std::max(d.max, diff);
      d.mean += diff;
      d.meanVisibility += a[f][i];
      d.differing += diff > 0 ? 1 : 0;
      d.beyond += diff > kPixelTolerance ? 1 : 0;
      d.computeBrighter += diff > kPixelTolerance && a[f][i] > b[f][i] ? 1 : 0;
      ++d.pixels;
    }
  d.mean /= double(d.pixels);
  d.meanVisibility /= double(d.pixels);
  return d;
}

// Same random numbers, same rays: the two traversals differ only where a ray meets a triangle's
// edge or a hit's t is rounded differently (README). Over every frame of a still and a moving
// shipped capture, in the seed's defaults and the reference's binary definition.
TEST(Rtao, RayQueryGivesTheComputeImageWithinTheTolerance) {
  if (std::string missing = missingRayQuery(); !missing.empty()) GTEST_SKIP() << skipReason(missing);
  ContextScope context(rayQueryContext());
  ASSERT_TRUE(context.vk.enabled(kRayQueryExtension));
  const std::vector<std::pair<std::string, std::string>> occlusions = {{"distance_based=1", "power=2"},
                                                                        {"distance_based=0", "power=1"}};
  for (const char* name : {"boxes-static", "boxes-orbit"})
    for (const auto& [occlusion, power] : occlusions) {
      Capture capture = loadCapture(fs::path(AOR_SOURCE_DIR) / "captures" / name);
      std::vector<std::string> settings = {occlusion, power, "traversal=compute"};
      auto compute = replayedVisibility(context.vk, capture, settings);
      settings.back() = "traversal=rayquery";
      auto rayQuery = replayedVisibility(context.vk, capture, settings);
      ASSERT_EQ(compute.size(), capture.frames.size());
      ASSERT_EQ(rayQuery.size(), compute.size());
      PathDifference d = differenceOf(compute, rayQuery);
      std::printf("rtao %s %s: %zu frames, mean visibility %.4f; |compute - rayquery| max %.3g mean %.3g; %zu of %zu "
                  "pixels differ, %zu by more than %g (%zu of them brighter in the compute path)\n",
                  name, occlusion.c_str(), compute.size(), d.meanVisibility, d.max, d.mean, d.differing, d.pixels, d.beyond,
                  kPixelTolerance, d.computeBrighter);
      EXPECT_LT(d.meanVisibility, 0.95) << "the rays must hit something for the comparison to mean anything";
      EXPECT_LE(d.mean, kMeanTolerance) << name << " " << occlusion;
      EXPECT_LE(double(d.beyond), kDifferingFraction * double(d.pixels)) << name << " " << occlusion;
    }
  destroyContext(context.vk);
  EXPECT_EQ(context.vk.validationMessageCount(), 0u);
}

// `auto` traces with ray queries on a device that has them (the run enables the extensions), the
// same triangles as the BVH, validates clean and is bit-identical twice.
TEST(Rtao, TraversalAutoPicksRayQueryWhereTheDeviceHasIt) {
  if (std::string missing = missingRayQuery(); !missing.empty()) GTEST_SKIP() << skipReason(missing);
  fs::path capture = generatedCapture("boxes", "static", 64, 36, 3);
  std::vector<fs::path> outs;
  for (int run = 0; run < 2; ++run) {
    outs.push_back(scratchDir(fmt::format("rtao-auto-{}", run)) / "out");
    auto r = runAoreplay(fmt::format("run {} --technique rtao --validate --out {}", capture.string(), outs.back().string()));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("validation: 0 messages"), std::string::npos) << r.output;
  }
  for (int frame = 0; frame < 3; ++frame) {
    std::string name = fmt::format("ao/{:04}.exr", frame);
    EXPECT_EQ(readText(outs[0] / name), readText(outs[1] / name)) << name;
  }
  fs::path compute = scratchDir("rtao-auto-compute") / "out";
  auto r = runAoreplay(fmt::format("run {} --technique rtao --set traversal=compute --frames 0:1 --no-images --out {}",
                                   capture.string(), compute.string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  json report = reportOf(outs[0]);
  const json& as = report["technique_state"];
  EXPECT_EQ(as["rayquery"], 1.0) << as.dump();
  EXPECT_EQ(as["as_triangles"], reportOf(compute)["technique_state"]["bvh_triangles"]) << as.dump();
  EXPECT_GT(as["as_blas_bytes"].get<double>(), 0.0) << as.dump();
  EXPECT_EQ(as["as_bytes"].get<double>(), as["as_blas_bytes"].get<double>() + as["as_tlas_bytes"].get<double>());
  EXPECT_GE(report["setup_ms"].get<double>(), as["as_build_ms"].get<double>());
  EXPECT_GT(as["as_build_ms"].get<double>(), 0.0);
  EXPECT_EQ(accumulatedFrames(report), (std::vector<double>{1, 2, 3}));
}

}  // namespace
}  // namespace aor::test
