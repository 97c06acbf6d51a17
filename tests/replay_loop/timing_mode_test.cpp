// Isolated and overlapped timing (issue 19, item 1): the same outputs either way; with isolation no
// decode or sink of the tool runs while any frame's GPU work is being timed, and with overlap it
// does (so the check is not vacuous); the CLI's flags, defaults and preload budget.
#include <fstream>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "gpu_test_support.h"

namespace aor::test {
namespace {

namespace fs = std::filesystem;

struct Interval {
  double begin, end;
  bool overlaps(const Interval& o) const { return begin < o.end && o.begin < end; }
};

ReplayedFrames replayIn(TimingMode mode, const fs::path& path, uint64_t budget = kDefaultPreloadBudgetBytes) {
  Capture capture = loadCapture(path);
  ReplayOptions options(settingsOf(gtaoTechnique(), {}));
  options.timingMode = mode;
  options.preloadBudgetBytes = budget;
  ReplayedFrames out;
  out.result = replayCapture(validatedContext(), capture, options, [&](const FrameOutput& f) { out.frames.push_back(f); });
  return out;
}

// How many (host work, GPU window) pairs overlap: decodes and sinks against every frame's record
// and GPU wait on the replay thread.
int hostWorkDuringGpu(const ReplayResult& r) {
  std::vector<Interval> gpu, host;
  for (const auto& f : r.frames) {
    double start = f.hostStartMs + f.waitMs;
    gpu.push_back({start, start + f.recordMs + f.gpuWallMs});
    host.push_back({f.workerStartMs, f.workerStartMs + f.decodeMs + f.uploadMs});
    host.push_back({f.sinkStartMs, f.sinkStartMs + f.readbackMs + f.writeMs});
  }
  int overlaps = 0;
  for (const auto& h : host)
    for (const auto& g : gpu) overlaps += h.overlaps(g);
  return overlaps;
}

TEST(TimingMode, IsolatedAndOverlappedGiveTheSameOutputs) {
  auto path = generatedCapture("boxes", "cut", 64, 36, 6);
  auto isolated = replayIn(TimingMode::Isolated, path);
  auto overlapped = replayIn(TimingMode::Overlapped, path);
  auto chunked = replayIn(TimingMode::Isolated, path, 64 * 36 * 60);  // a few frames a chunk
  EXPECT_EQ(isolated.result.timingMode, TimingMode::Isolated);
  EXPECT_EQ(overlapped.result.timingMode, TimingMode::Overlapped);
  EXPECT_LT(chunked.result.chunkFrames, 6);
  EXPECT_GT(chunked.result.chunkFrames, 0);
  ASSERT_EQ(isolated.frames.size(), 6u);
  for (const auto* other : {&overlapped, &chunked}) {
    ASSERT_EQ(other->frames.size(), 6u);
    for (size_t k = 0; k < 6; ++k) {
      EXPECT_TRUE(bitIdentical(isolated.frames[k].visibility, other->frames[k].visibility)) << "frame " << k;
      EXPECT_TRUE(bitIdentical(isolated.frames[k].bent, other->frames[k].bent)) << "frame " << k;
      EXPECT_EQ(isolated.result.frames[k].resetReason, other->result.frames[k].resetReason) << "frame " << k;
    }
  }
}

TEST(TimingMode, IsolatedRunsNoHostWorkWhileAFrameIsTimed) {
  auto path = generatedCapture("boxes", "orbit", 64, 36, 6);
  auto isolated = replayIn(TimingMode::Isolated, path);
  EXPECT_EQ(hostWorkDuringGpu(isolated.result), 0);
  auto chunked = replayIn(TimingMode::Isolated, path, 64 * 36 * 60);
  EXPECT_EQ(hostWorkDuringGpu(chunked.result), 0);
  // Not vacuous: the pipelined replay decodes the next frame while the GPU runs this one.
  EXPECT_GT(hostWorkDuringGpu(replayIn(TimingMode::Overlapped, path).result), 0);
}

TEST(TimingMode, CliDefaultsToIsolatedOnLavapipeAndTakesTheFlags) {
  auto capture = generatedCapture("boxes", "orbit", 64, 36, 3);
  auto mode = [&](const std::string& flags) {
    fs::path out = scratchDir("mode") / "out";
    auto r = runAoreplay(fmt::format("run {} --no-images {} --out {}", capture.string(), flags, out.string()));
    EXPECT_EQ(r.exitCode, 0) << r.output;
    auto report = nlohmann::json::parse(std::ifstream(out / "report.json"));
    EXPECT_EQ(report["run"]["warmup"], flags.find("--warmup") == std::string::npos ? 1 : 0);
    return report["timing"]["mode"].get<std::string>();
  };
  EXPECT_EQ(mode(""), "isolated");
  EXPECT_EQ(mode("--overlap"), "overlapped");
  EXPECT_EQ(mode("--isolate --warmup 0"), "isolated");
  fs::path out = scratchDir("mode-bad") / "out";
  auto both = runAoreplay(fmt::format("run {} --overlap --isolate --out {}", capture.string(), out.string()));
  EXPECT_EQ(both.exitCode, 2) << both.output;
  EXPECT_NE(both.output.find("--overlap and --isolate exclude each other"), std::string::npos) << both.output;
  EXPECT_FALSE(fs::exists(out));
}

TEST(TimingMode, APreloadBudgetTooSmallForOneFrameIsBadInput) {
  // One 320x180 frame with normals needs about 2 MiB preloaded.
  fs::path capture = fs::path(AOR_SOURCE_DIR) / "captures" / "boxes-orbit";
  fs::path out = scratchDir("budget") / "out";
  auto r = runAoreplay(fmt::format("run {} --frames 0:2 --preload-budget 1 --out {}", capture.string(), out.string()));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("--preload-budget"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("one frame of this capture needs"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
  // The same budget is no error where nothing is preloaded.
  r = runAoreplay(fmt::format("run {} --frames 0:2 --preload-budget 1 --overlap --no-images --out {}", capture.string(),
                              out.string()));
  EXPECT_EQ(r.exitCode, 0) << r.output;
}

}  // namespace
}  // namespace aor::test
