// The aoreplay binary as users and their CI call it: outputs, determinism across processes and
// thread counts, validation, exit codes and no partial results on failure.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "capture/image_io.h"
#include "gpu_test_support.h"
#include "scratch_folder.h"
#include "report/compare.h"

namespace aor::test {
namespace {
namespace fs = std::filesystem;

std::vector<float> visibilityOf(const fs::path& exr) {
  return readExrChannels(exr, {"visibility"}).at("visibility");
}

class Cli : public ::testing::Test {
 protected:
  static fs::path capture() { return generatedCapture("boxes", "orbit", 64, 36, 3); }
};

TEST_F(Cli, RunWritesImagesReportAndTraceWithPerPassTimes) {
  auto out = scratchDir("cli-run") / "result";
  auto r = runAoreplay(fmt::format("run {} --out {} --repeat 3 --warmup 1", capture().string(), out.string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* pass : {"gtao", "spatial", "temporal"}) EXPECT_NE(r.output.find(pass), std::string::npos) << pass;
  EXPECT_NE(r.output.find(out.string()), std::string::npos) << "the run says where its outputs went";
  for (int i = 0; i < 3; ++i) {
    EXPECT_TRUE(fs::exists(out / "ao" / fmt::format("{:04d}.exr", i)));
    EXPECT_TRUE(fs::exists(out / "ao" / fmt::format("{:04d}.png", i)));
  }
  auto header = readExrHeader(out / "ao" / "0000.exr");
  EXPECT_EQ(header.channels.count("visibility"), 1u);
  EXPECT_EQ(header.channels.count("bent.X"), 1u);

  auto report = readJsonFile(out / "report.json");
  std::map<std::string, nlohmann::json> passes;
  for (const auto& p : report["passes"]) passes[p["name"]] = p;
  for (const char* pass : {"gtao", "spatial", "temporal"}) {
    ASSERT_TRUE(passes.count(pass)) << pass;
    auto ms = passes[pass]["gpu_ms"];
    EXPECT_EQ(ms["count"].get<int>(), 9) << "3 frames x 3 timed repetitions";
    EXPECT_GT(ms["median"].get<double>(), 0.0);
    EXPECT_LE(ms["min"].get<double>(), ms["median"].get<double>());
    EXPECT_LE(ms["median"].get<double>(), ms["max"].get<double>());
  }
  // The total is the pipeline's (compute passes), as compare's and ao_bench's: the median over
  // the 9 timed runs of each run's sum of the compute passes. Every pass ran in every frame here,
  // so sample k of every pass is the same timed run. The host copies are summed apart, alike.
  std::vector<double> computeSums(9, 0.0), hostCopySums(9, 0.0);
  for (const auto& [name, p] : passes) {
    auto samples = p["gpu_ms"]["samples"].get<std::vector<double>>();
    ASSERT_EQ(samples.size(), 9u) << name;
    for (size_t k = 0; k < samples.size(); ++k) (name == "upload" || name == "readback" ? hostCopySums : computeSums)[k] += samples[k];
  }
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  double computeMs = median(computeSums), hostCopyMs = median(hostCopySums);
  ASSERT_TRUE(passes.count("upload") && passes.count("readback"));
  EXPECT_GT(hostCopyMs, 0.0);
  EXPECT_NEAR(report["gpu_ms_total_median"].get<double>(), computeMs, 1e-9 * computeMs);
  EXPECT_NEAR(report["gpu_ms_host_copies_median"].get<double>(), hostCopyMs, 1e-9 * hostCopyMs);
  EXPECT_NE(r.output.find(fmt::format("host copies add {:.3f}", hostCopyMs)), std::string::npos) << r.output;
  // compare reads the same total back from the report: its one value for this run.
  auto timings = loadTimingSamples(out / "report.json");
  auto total = std::find_if(timings.begin(), timings.end(), [](const auto& s) { return s.name == "total"; });
  ASSERT_NE(total, timings.end());
  EXPECT_EQ(total->runValue(), report["gpu_ms_total_median"].get<double>());
  EXPECT_EQ(total->samples.size(), 9u);
  EXPECT_EQ(report["frames"][0]["history"], "reset");
  EXPECT_EQ(report["frames"][0]["reset_reason"], "first frame");
  EXPECT_EQ(report["frames"][1]["history"], "valid");
  std::vector<std::string> culled;
  for (const auto& c : report["culled_passes"]) culled.push_back(c["name"]);
  // The shared front's normal blocks: gtao reads the capture's world normals itself.
  EXPECT_EQ(culled, (std::vector<std::string>{"reconstruct_normals", "view_normals"}));

  auto trace = readJsonFile(out / "trace.json");
  std::set<int> tracks;
  for (const auto& e : trace["traceEvents"])
    if (e["ph"] == "X") tracks.insert(e["tid"].get<int>());
  EXPECT_EQ(tracks.size(), 4u) << "GPU passes, the replay thread, the decode worker and the sink worker";
}

// What the host adds to a replay is reported, and decoding runs ahead of the GPU on a worker.
TEST_F(Cli, ReportBreaksDownHostTimeAndDecodesAheadOfTheGpu) {
  auto out = scratchDir("cli-host") / "result";
  // 30 untimed executions per frame make frame 0's GPU window some milliseconds long at 64x36, so
  // frame 1's decode, started on a worker as frame 0 is submitted, starts inside it even when the
  // worker thread takes a while to start on a loaded machine. (Pipeline compilation used to make
  // that window long; it now happens in the set-up.) Overlapped timing: isolated timing, lavapipe's
  // default, decodes before and writes after the GPU work (timing_mode_test.cpp).
  auto r = runAoreplay(fmt::format("run {} --out {} --no-images --warmup 30 --overlap", capture().string(), out.string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  auto report = readJsonFile(out / "report.json");
  double gpu = 0;
  for (const auto& frame : report["frames"]) {
    for (const char* part : {"decode", "upload", "wait", "record", "gpu", "readback", "write"}) {
      ASSERT_TRUE(frame["host_ms"].contains(part)) << part;
      EXPECT_GE(frame["host_ms"][part].get<double>(), 0.0) << part;
    }
    EXPECT_GT(frame["host_ms"]["decode"].get<double>(), 0.0);
    EXPECT_GT(frame["host_ms"]["write"].get<double>(), 0.0) << "the sink analyses every frame";
    gpu += frame["host_ms"]["gpu"].get<double>();
  }
  double wall = report["wall_ms"].get<double>();
  EXPECT_NEAR(report["host_overhead"]["ms"].get<double>(), wall - gpu, 1e-6 * wall);
  EXPECT_NEAR(report["host_overhead"]["fraction_of_wall"].get<double>(), (wall - gpu) / wall, 1e-9);
  EXPECT_NE(r.output.find("host overhead"), std::string::npos) << r.output;

  // Frame 0 is decoded during the set-up (which compiles the pipelines), frame 1 while frame 0 runs
  // on the GPU.
  double setupMs = report["setup_ms"].get<double>();
  EXPECT_GT(setupMs, 0.0);
  auto trace = readJsonFile(out / "trace.json");
  double decode0Start = -1, decode1Start = -1, gpu0End = -1;
  for (const auto& e : trace["traceEvents"]) {
    if (e["ph"] != "X" || !e["args"].contains("frame")) continue;
    int frame = e["args"]["frame"].get<int>();
    if (e["name"] == "decode" && frame == 0) decode0Start = e["ts"].get<double>();
    if (e["name"] == "decode" && frame == 1) decode1Start = e["ts"].get<double>();
    if (e["name"] == "gpu (submit + wait)" && frame == 0) gpu0End = e["ts"].get<double>() + e["dur"].get<double>();
  }
  ASSERT_GE(decode0Start, 0.0);
  ASSERT_GE(decode1Start, 0.0);
  ASSERT_GE(gpu0End, 0.0);
  EXPECT_LT(decode0Start, setupMs * 1000.0);  // trace times are microseconds
  EXPECT_LT(decode1Start, gpu0End);
}

TEST_F(Cli, OutputsAreBitIdenticalAcrossRunsAndLavapipeThreadCounts) {
  auto dir = scratchDir("cli-determinism");
  auto args = [&](const char* name) { return fmt::format("run {} --out {}", capture().string(), (dir / name).string()); };
  ASSERT_EQ(runAoreplay(args("a")).exitCode, 0);
  ASSERT_EQ(runAoreplay(args("b")).exitCode, 0);
  ASSERT_EQ(runAoreplay(args("one-thread"), "LP_NUM_THREADS=1").exitCode, 0);
  for (int i = 0; i < 3; ++i) {
    auto name = fmt::format("{:04d}.exr", i);
    auto a = visibilityOf(dir / "a" / "ao" / name);
    EXPECT_TRUE(bitIdentical(a, visibilityOf(dir / "b" / "ao" / name))) << name;
    EXPECT_TRUE(bitIdentical(a, visibilityOf(dir / "one-thread" / "ao" / name))) << name;
  }
}

TEST_F(Cli, ValidateOnTheShippedCaptureReportsZeroMessages) {
  auto out = scratchDir("cli-validate") / "result";
  auto shipped = fs::path(AOR_SOURCE_DIR) / "captures" / "boxes-orbit";
  auto r = runAoreplay(fmt::format("run {} --validate --no-images --out {}", shipped.string(), out.string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  auto report = readJsonFile(out / "report.json");
  EXPECT_TRUE(report["validation"]["enabled"].get<bool>());
  EXPECT_EQ(report["validation"]["messages"].get<int>(), 0);
  EXPECT_EQ(report["frames"].size(), loadCapture(shipped).frames.size());
  EXPECT_NE(r.output.find("validation: 0 messages"), std::string::npos);
}

struct BadRun {
  std::string arguments;
  int exitCode;
  std::string mentions;
};

TEST_F(Cli, BadUsageAndInputExitWithTwoAndNoDeviceWithThree) {
  auto dir = scratchDir("cli-bad");
  std::string cap = capture().string();
  std::vector<BadRun> cases = {
      {"run " + (dir / "missing").string(), 2, "missing"},
      {"run " + cap + " --set foo=1", 2, "foo"},
      {"run " + cap + " --set slices=0", 2, "slices"},
      {"run " + cap + " --set temporal=0.99", 2, "temporal"},
      {"run " + cap + " --set radius=abc", 2, "radius"},
      {"run " + cap + " --preset extreme", 2, "extreme"},
      {"run " + cap + " --frames 2:1", 2, "--frames"},
      {"run " + cap + " --frames 0:99", 2, "--frames"},
      {"run " + cap + " --repeat 0", 2, "repeat"},
      {"run " + cap + " --no-such-flag", 2, "no-such-flag"},
      {"run " + cap + " --device no-such-gpu-anywhere", 3, "no-such-gpu-anywhere"},
  };
  for (const auto& c : cases) {
    auto out = dir / "out";
    auto r = runAoreplay(c.arguments + " --out " + out.string());
    EXPECT_EQ(r.exitCode, c.exitCode) << c.arguments << "\n" << r.output;
    EXPECT_NE(r.output.find(c.mentions), std::string::npos) << c.arguments << "\n" << r.output;
    EXPECT_FALSE(fs::exists(out)) << c.arguments << " left an output folder";
    for (const auto& entry : fs::directory_iterator(dir)) ADD_FAILURE() << "left behind: " << entry.path();
  }
}

TEST_F(Cli, GraphCommandExplainsCulledPassesAndWritesDot) {
  auto dot = scratchDir("cli-graph") / "graph.dot";
  auto r = runAoreplay(fmt::format("graph {} --frames 0:1 --dot {}", capture().string(), dot.string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("temporal"), std::string::npos);
  EXPECT_NE(r.output.find("single-frame"), std::string::npos);
  EXPECT_NE(r.output.find("the capture has normals"), std::string::npos);
  ASSERT_TRUE(fs::exists(dot));
  if (std::system("command -v dot > /dev/null") == 0) {
    EXPECT_EQ(std::system(fmt::format("dot -Tsvg {} -o {}.svg", dot.string(), dot.string()).c_str()), 0);
  }
  // Two frames: the second one's history starts where the first left it, as in a replay.
  r = runAoreplay(fmt::format("graph {} --frames 0:2 --dot {}", capture().string(), dot.string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("barrier ao_history.previous: TRANSFER_SRC_OPTIMAL -> GENERAL"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("ao_history.previous: UNDEFINED"), std::string::npos) << r.output;
}

// Everything under `dir` (relative paths, folders included), to see what a command left behind.
std::set<std::string> listing(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) names.insert(fs::relative(entry.path(), dir).string());
  return names;
}

// Committing a result replaces --out, i.e. deletes it: only an earlier result (or an empty folder)
// may be replaced, and the refusal comes before any replay.
TEST_F(Cli, RunAndSweepReplaceOnlyEarlierResults) {
  auto dir = scratchDir("cli-out-guard");
  std::string cap = capture().string();
  auto precious = dir / "precious";
  fs::create_directories(precious);
  std::ofstream(precious / "notes.txt") << "keep me";
  std::ofstream(dir / "file.txt") << "keep me too";
  for (const char* command : {"run", "sweep"}) {
    for (const auto& out : {precious, dir / "file.txt", dir / "file.txt" / "below"}) {
      auto r = runAoreplay(fmt::format("{} {} --frames 0:1 --out {}", command, cap, out.string()));
      EXPECT_EQ(r.exitCode, 2) << command << " " << out << "\n" << r.output;
      EXPECT_NE(r.output.find(out.string()), std::string::npos) << r.output;
      EXPECT_NE(r.output.find("--out"), std::string::npos) << r.output;
    }
  }
  EXPECT_EQ(listing(dir), (std::set<std::string>{"file.txt", "precious", "precious/notes.txt"}));
  EXPECT_EQ(readText(precious / "notes.txt"), "keep me");

  auto earlier = dir / "earlier";
  ASSERT_EQ(runAoreplay(fmt::format("run {} --frames 0:1 --no-images --out {}", cap, earlier.string())).exitCode, 0);
  auto again = runAoreplay(fmt::format("run {} --frames 0:2 --no-images --out {}", cap, earlier.string()));
  EXPECT_EQ(again.exitCode, 0) << again.output;
  EXPECT_EQ(readJsonFile(earlier / "report.json")["frames"].size(), 2u) << "the earlier result was replaced";
}

TEST_F(Cli, GraphCommandRefusesAnUnwritableDotPathAndLeavesNothingBehind) {
  auto dir = scratchDir("cli-graph-unwritable");
  fs::create_directory(dir / "folder");
  std::ofstream(dir / "file") << "a regular file\n";
  auto before = listing(dir);
  for (const fs::path& dot : {dir / "folder", dir / "file" / "graph.dot", dir / "file" / "sub" / "graph.dot",
                              dir / "new" / ""}) {
    auto r = runAoreplay(fmt::format("graph {} --frames 0:1 --dot {}", capture().string(), dot.string()));
    EXPECT_EQ(r.exitCode, 2) << dot << "\n" << r.output;
    EXPECT_NE(r.output.find("aoreplay: error: " + dot.string() + ": "), std::string::npos) << dot << "\n" << r.output;
    EXPECT_EQ(r.output.find("\ndot: "), std::string::npos) << dot << " claims to be written\n" << r.output;
    EXPECT_EQ(listing(dir), before) << dot << " left something behind";
  }
  EXPECT_EQ(readText(dir / "file"), "a regular file\n");
}

TEST_F(Cli, GraphCommandReplacesAnExistingDotFileWhole) {
  auto dir = scratchDir("cli-graph-replace");
  auto dot = dir / "graph.dot";
  std::ofstream(dot) << "old contents\n";
  auto r = runAoreplay(fmt::format("graph {} --frames 0:1 --dot {}", capture().string(), dot.string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(readText(dot).rfind("digraph render_graph {", 0), 0u) << readText(dot);
  EXPECT_EQ(listing(dir), std::set<std::string>{"graph.dot"}) << "no temporary file stays beside it";
}

}  // namespace
}  // namespace aor::test
