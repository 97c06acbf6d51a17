// Issue 20, "Why": every way a hostile or careless user lost data, crashed, hung or got a wrong
// answer accepted, as the aoreplay binary is called. Each ends in exit 2 (or the stated outcome
// for concurrency) and nothing the user had is lost: folders are compared by hash before and after.
#include <sys/stat.h>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "gpu_test_support.h"
#include "output_test_support.h"

namespace aor::test {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

fs::path capture() { return generatedCapture("boxes", "orbit", 32, 18, 2); }

// A private copy of the capture, so a test may put things into it.
fs::path captureCopy(const fs::path& dir) {
  fs::copy(capture(), dir / "capture", fs::copy_options::recursive);
  return dir / "capture";
}

std::string run(const fs::path& cap, const fs::path& out, int frames = 2) {
  return fmt::format("run '{}' --out '{}' --frames 0:{}", cap.string(), out.string(), frames);
}

void writeText(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary | std::ios::trunc) << text; }

// ---- data loss ------------------------------------------------------------------------------------------

TEST(OutputSafety, OutAtTheCaptureFolderHoldingAReportIsRefusedAndTheCaptureSurvives) {
  auto dir = scratchDir("out-is-capture");
  auto cap = captureCopy(dir);
  ASSERT_EQ(runAoreplay(run(cap, dir / "earlier")).exitCode, 0);
  fs::copy_file(dir / "earlier" / "report.json", cap / "report.json");
  const auto before = treeHashes(cap);
  for (const fs::path& out : {cap, cap / "frames", cap / "sub" / "result", dir}) {
    auto r = runAoreplay(run(cap, out));
    EXPECT_EQ(r.exitCode, 2) << out << "\n" << r.output;
    EXPECT_NE(r.output.find("an input of this run"), std::string::npos) << r.output;
  }
  EXPECT_EQ(treeHashes(cap), before);
}

TEST(OutputSafety, AnUnrelatedFileBesideAReportIsNeverDeleted) {
  auto dir = scratchDir("unrelated-file");
  auto out = dir / "result";
  ASSERT_EQ(runAoreplay(run(capture(), out)).exitCode, 0);
  writeText(out / "notes.txt", "mine");
  fs::create_directories(out / "ao" / "mine");
  writeText(out / "ao" / "mine" / "a.txt", "also mine");
  const auto before = treeHashes(out);
  auto r = runAoreplay(run(capture(), out, 1));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("\"ao/mine\", which aoreplay did not write there"), std::string::npos) << r.output;
  r = runAoreplay(fmt::format("sweep '{}' --frames 0:1 --out '{}'", capture().string(), out.string()));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("holds an aoreplay \"run\" result, not a sweep result"), std::string::npos) << r.output;
  EXPECT_EQ(treeHashes(out), before);
  EXPECT_EQ(namesIn(dir), std::set<std::string>{"result"}) << "no staging folder or lock left beside it";
}

TEST(OutputSafety, AnOlderResultWithoutTheMarkerIsReplacedOnlyWhenItHoldsNothingElse) {
  auto dir = scratchDir("legacy-result");
  auto out = dir / "result";
  ASSERT_EQ(runAoreplay(run(capture(), out, 1)).exitCode, 0);
  fs::remove(out / ".aoreplay-result.json");  // as written before issue 20
  auto again = runAoreplay(run(capture(), out));
  ASSERT_EQ(again.exitCode, 0) << again.output;
  EXPECT_EQ(completeRunFrames(out), 2u);
  // Without the marker, a report.json that is not aoreplay's does not make a folder a result.
  fs::remove(out / ".aoreplay-result.json");
  writeText(out / "report.json", "{\"tool\": \"someone else\"}");
  const auto before = treeHashes(out);
  auto r = runAoreplay(run(capture(), out));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("no report.json written by aoreplay"), std::string::npos) << r.output;
  EXPECT_EQ(treeHashes(out), before);
}

TEST(OutputSafety, ASecondRunOnTheSameOutExitsTwoNamingTheFirstOnesProcess) {
  auto dir = scratchDir("two-writers");
  auto out = dir / "result";
  ASSERT_EQ(runAoreplay(run(capture(), out)).exitCode, 0);
  const auto before = treeHashes(out);
  // The first run stops itself right after it took the lock; the second runs meanwhile.
  pid_t first = spawnAoreplay({"run", capture().string(), "--out", out.string(), "--frames", "0:1"},
                              {"AOREPLAY_TEST_STOP_AFTER=locked"});
  ASSERT_GT(first, 0);
  ASSERT_TRUE(WIFSTOPPED(waitFor(first, WUNTRACED)));
  for (const char* command : {"run", "sweep"}) {
    auto second = runAoreplay(fmt::format("{} '{}' --frames 0:1 --out '{}'", command, capture().string(), out.string()));
    EXPECT_EQ(second.exitCode, 2) << second.output;
    EXPECT_NE(second.output.find(fmt::format("being written by another aoreplay run (process {}", first)),
              std::string::npos)
        << second.output;
  }
  EXPECT_EQ(treeHashes(out), before) << "the refused run changed nothing";
  kill(first, SIGCONT);
  const int status = waitFor(first);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_EQ(completeRunFrames(out), 1u) << "the first run's result is the one in place";
  EXPECT_EQ(namesIn(dir), std::set<std::string>{"result"});
}

TEST(OutputSafety, AFileCreatedInOutDuringARunSurvivesAndTheRunSaysSo) {
  auto dir = scratchDir("file-during-run");
  auto out = dir / "result";
  ASSERT_EQ(runAoreplay(run(capture(), out)).exitCode, 0);
  pid_t writer = spawnAoreplay({"run", capture().string(), "--out", out.string(), "--frames", "0:1"},
                               {"AOREPLAY_TEST_STOP_AFTER=staged"});
  ASSERT_GT(writer, 0);
  ASSERT_TRUE(WIFSTOPPED(waitFor(writer, WUNTRACED)));
  writeText(out / "appeared.txt", "written while the run was replaying");
  const auto before = treeHashes(out);
  kill(writer, SIGCONT);
  const int status = waitFor(writer);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2);
  EXPECT_EQ(treeHashes(out), before) << "the earlier result and the new file are as they were";
  EXPECT_EQ(namesIn(dir), std::set<std::string>{"result"}) << "the discarded result's staging is gone";
}

TEST(OutputSafety, AnEarlierResultThatCannotBeRemovedIsRefusedBeforeAnyWork) {
  auto dir = scratchDir("read-only-subfolder");
  auto out = dir / "result";
  ASSERT_EQ(runAoreplay(run(capture(), out, 1)).exitCode, 0);
  fs::permissions(out / "ao", fs::perms::owner_write | fs::perms::group_write | fs::perms::others_write,
                  fs::perm_options::remove);
  const auto before = treeHashes(out);
  auto r = runAoreplay(run(capture(), out));
  if (geteuid() == 0) {
    // Root may remove files from a read-only folder: the replacement goes through, whole.
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(completeRunFrames(out), 2u);
  } else {
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("\"ao/\" is not writable"), std::string::npos) << r.output;
    EXPECT_EQ(treeHashes(out), before) << "the old report.json and trace.json are still there";
    fs::permissions(out / "ao", fs::perms::owner_write, fs::perm_options::add);
  }
  EXPECT_EQ(namesIn(dir), std::set<std::string>{"result"});
}

TEST(OutputSafety, StagingAndLocksOfDeadRunsAreRemovedByTheNextRun) {
  auto dir = scratchDir("dead-staging");
  auto out = dir / "result";
  ASSERT_EQ(runAoreplay(run(capture(), out)).exitCode, 0);
  fs::create_directories(dir / ".result.tmp-999999999" / "ao");
  writeText(dir / ".result.tmp-999999999" / "ao" / "0000.exr", "half written");
  writeText(dir / ".result.lock", "999999999\n");
  writeText(dir / ".result.tmp-not-a-pid", "not ours");  // a name aoreplay never makes stays
  auto r = runAoreplay(run(capture(), out));
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(namesIn(dir), (std::set<std::string>{"result", ".result.tmp-not-a-pid"}));
}

TEST(OutputSafety, FileOutputsRefuseLinksFifosFoldersAndInputsAndTakeStandardOutput) {
  auto dir = scratchDir("file-outputs");
  ASSERT_EQ(runAoreplay(run(capture(), dir / "a")).exitCode, 0);
  const auto report = dir / "a" / "report.json";
  writeText(dir / "target.json", "the link's target");
  fs::create_symlink(dir / "target.json", dir / "link.json");
  ASSERT_EQ(mkfifo((dir / "fifo.json").c_str(), 0600), 0);
  for (const fs::path& json : {dir / "link.json", dir / "fifo.json", fs::path(report)}) {
    auto r = runAoreplay(fmt::format("compare '{}' '{}' --json '{}'", report.string(), report.string(), json.string()),
                         "timeout 120");
    EXPECT_EQ(r.exitCode, 2) << json << "\n" << r.output;
  }
  EXPECT_TRUE(fs::is_symlink(dir / "link.json"));
  EXPECT_EQ(fileBytes(dir / "target.json"), "the link's target");
  EXPECT_TRUE(fs::is_fifo(dir / "fifo.json"));
  EXPECT_EQ(completeRunFrames(dir / "a"), 2u) << "the input report is untouched";
  auto cap = captureCopy(dir);
  const auto captureBefore = treeHashes(cap);
  auto dot = runAoreplay(fmt::format("graph '{}' --dot '{}'", cap.string(), (cap / "capture.json").string()));
  EXPECT_EQ(dot.exitCode, 2) << dot.output;
  EXPECT_NE(dot.output.find("an input of this run"), std::string::npos) << dot.output;
  EXPECT_EQ(treeHashes(cap), captureBefore);

  // "-": the verdicts (or the graph) on standard output, the human text on standard error.
  const auto stdoutFile = dir / "stdout.json";
  const std::string compare = fmt::format("{} compare '{}' '{}' --json - > '{}' 2> '{}'", AOR_EXE, report.string(),
                                          report.string(), stdoutFile.string(), (dir / "stderr.txt").string());
  ASSERT_EQ(std::system(compare.c_str()), 0);
  EXPECT_TRUE(json::parse(fileBytes(stdoutFile)).contains("passes"));
  EXPECT_NE(fileBytes(dir / "stderr.txt").find("verdict"), std::string::npos);
  const std::string graph = fmt::format("{} graph '{}' --dot - > '{}' 2> /dev/null", AOR_EXE, capture().string(),
                                        (dir / "graph.dot").string());
  ASSERT_EQ(std::system(graph.c_str()), 0);
  EXPECT_EQ(fileBytes(dir / "graph.dot").rfind("digraph render_graph {", 0), 0u);
}

TEST(OutputSafety, CaptureRefusesAFolderItDidNotWriteBeforeRendering) {
  auto dir = scratchDir("capture-out");
  fs::create_directories(dir / "precious");
  writeText(dir / "precious" / "capture.json", "{\"format\": \"aoreplay-capture\"}");
  writeText(dir / "precious" / "notes.txt", "mine");
  const auto before = treeHashes(dir / "precious");
  auto r = runAoreplay(fmt::format("capture boxes --size 32x18 --frames 2 --out '{}'", (dir / "precious").string()));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_EQ(treeHashes(dir / "precious"), before);
  EXPECT_EQ(namesIn(dir), std::set<std::string>{"precious"});
}

// ---- crashes, hangs, wrong answers -------------------------------------------------------------------

TEST(InputSafety, DeepLongAndOutOfRangeCapturesExitTwo) {
  struct Case {
    std::string name, mentions;
    std::function<void(json&)> edit;
  };
  std::string deep;
  const std::vector<Case> cases = {
      {"radius-overflow", "scene.ao_radius", [](json& d) { d["scene"]["ao_radius"] = 1e300; }},
      {"radius-underflow", "scene.ao_radius", [](json& d) { d["scene"]["ao_radius"] = 1e-300; }},
      {"radius-not-a-number", "scene.ao_radius", [](json& d) { d["scene"]["ao_radius"] = "1"; }},
      {"long-unknown-key", "unknown field", [](json& d) { d[std::string(1 << 21, 'k')] = 1; }},
  };
  for (const auto& c : cases) {
    auto dir = scratchDir(c.name);
    auto cap = captureCopy(dir);
    json doc = json::parse(fileBytes(cap / "capture.json"));
    c.edit(doc);
    writeText(cap / "capture.json", doc.dump());
    auto r = runAoreplay(run(cap, dir / "out"));
    EXPECT_EQ(r.exitCode, 2) << c.name << "\n" << r.output.substr(0, 500);
    EXPECT_NE(r.output.find(c.mentions), std::string::npos) << r.output.substr(0, 500);
    EXPECT_LT(r.output.size(), 600u) << c.name << ": a long value is not echoed whole";
    EXPECT_FALSE(fs::exists(dir / "out"));
  }
  auto dir = scratchDir("deep-scene");
  auto cap = captureCopy(dir);
  std::string text = fileBytes(cap / "capture.json");
  for (int i = 0; i < 60000; ++i) deep += "{\"a\":";
  deep += "1" + std::string(60000, '}');
  text.insert(text.find("\"scene\": {") + 10, "\"deep\": " + deep + ",");
  writeText(cap / "capture.json", text);
  auto r = runAoreplay(run(cap, dir / "out"));
  EXPECT_EQ(r.exitCode, 2) << r.output.substr(0, 500);
  EXPECT_NE(r.output.find("nested deeper than 128 levels"), std::string::npos) << r.output.substr(0, 500);
}

TEST(InputSafety, ExpectFilesThatAreDeepDuplicatedOrFifosExitTwo) {
  auto dir = scratchDir("expect");
  writeText(dir / "deep.json", "{\"max\": {\"error.rmse\": " + std::string(100000, '[') + "1" + std::string(100000, ']') + "}}");
  // The stricter threshold first: with duplicates accepted, the last one silently won.
  writeText(dir / "duplicate.json", R"({"max": {"error.rmse": 0.000001}, "max": {"error.rmse": 1}})");
  ASSERT_EQ(mkfifo((dir / "fifo.json").c_str(), 0600), 0);
  for (const char* name : {"deep.json", "duplicate.json", "fifo.json"}) {
    // timeout: a run that blocks on the FIFO fails the test (124) instead of hanging it.
    auto r = runAoreplay(fmt::format("run '{}' --frames 0:1 --out '{}' --expect '{}'", capture().string(),
                                     (dir / "out").string(), (dir / name).string()),
                         "timeout 120");
    EXPECT_EQ(r.exitCode, 2) << name << "\n" << r.output;
    EXPECT_NE(r.output.find(name), std::string::npos) << r.output;
  }
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST(InputSafety, CompareOnFifosMistypedFieldsAndLongNamesGivesExitTwoOrAVerdictNeverACrash) {
  auto dir = scratchDir("compare");
  ASSERT_EQ(runAoreplay(run(capture(), dir / "a")).exitCode, 0);
  const auto report = (dir / "a" / "report.json").string();
  ASSERT_EQ(mkfifo((dir / "fifo.json").c_str(), 0600), 0);
  auto r = runAoreplay(fmt::format("compare '{}' '{}'", report, (dir / "fifo.json").string()), "timeout 120");
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("not a regular file"), std::string::npos) << r.output;

  struct Mistyped {
    std::string text, field;
  };
  const std::vector<Mistyped> mistyped = {
      {R"({"tool": 5})", "field \"tool\""},
      {R"({"benchmarks": [{"name": "a", "real_time": 1, "time_unit": true}]})", "field \"benchmarks[0].time_unit\""},
      {R"({"benchmarks": [{"name": 7, "real_time": 1}]})", "field \"benchmarks[0].name\""},
      {R"({"benchmarks": [{"name": "a", "run_type": [], "real_time": 1}]})", "field \"benchmarks[0].run_type\""},
      {R"({"benchmarks": [{"name": "a", "error_occurred": "yes", "real_time": 1}]})", "field \"benchmarks[0].error_occurred\""},
      {R"({"benchmarks": [3]})", "field \"benchmarks[0]\""},
      {R"({"tool": "aoreplay", "passes": [{"name": "gtao", "gpu_ms": {"samples": ["1"]}}]})",
       "field \"passes[0].gpu_ms.samples[0]\""},
  };
  for (const auto& m : mistyped) {
    writeText(dir / "bad.json", m.text);
    r = runAoreplay(fmt::format("compare '{}' '{}'", report, (dir / "bad.json").string()));
    EXPECT_EQ(r.exitCode, 2) << m.text << "\n" << r.output;
    EXPECT_NE(r.output.find("bad.json: " + m.field), std::string::npos) << m.text << "\n" << r.output;
  }

  // A 50 000-character pass name and --ignore 'x+': std::regex overflowed the stack on it.
  json doc = json::parse(fileBytes(dir / "a" / "report.json"));
  json pass = doc["passes"][0];
  const std::string longName(50000, 'x');
  pass["name"] = longName;
  doc["passes"].push_back(pass);
  // Every frame lists the passes it ran (compare checks the samples against them).
  for (auto& frame : doc["frames"]) frame["gpu_ms_median"][longName] = frame["gpu_ms_median"][doc["passes"][0]["name"].get<std::string>()];
  writeText(dir / "long.json", doc.dump());
  r = runAoreplay(fmt::format("compare '{}' '{}' --ignore 'x+'", (dir / "long.json").string(), (dir / "long.json").string()));
  EXPECT_EQ(r.exitCode, 0) << r.output.substr(0, 500);
  EXPECT_EQ(r.output.find("xxxxxxxxxx"), std::string::npos) << "the long name was ignored";
  EXPECT_NE(r.output.find("gtao"), std::string::npos);
}

}  // namespace
}  // namespace aor::test
