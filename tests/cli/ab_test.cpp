// `aoreplay ab`: ABBA order of fresh processes, every run kept under DIR/a/ and DIR/b/, the verdict
// of `compare DIR/a DIR/b`, its exit codes, and no partial output on failure. Most tests run a
// stand-in `aoreplay` (a shell script writing a report.json with the times it is told) so the
// verdicts are known; one runs the real binary on a small capture.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "gpu_test_support.h"
#include "scratch_folder.h"
#include "report/compare.h"

namespace aor::test {
namespace {
namespace fs = std::filesystem;

// `STUB run CAPTURE [--ms GTAO_MS] [--label L --log FILE] [--fail STATUS] --out DIR`: appends L to
// FILE, then exits STATUS or writes DIR/report.json: one frame, three timed repetitions of gtao
// (about GTAO_MS) and spatial (about 1 ms).
fs::path stubBinary(const fs::path& dir) {
  fs::path stub = dir / "stub-aoreplay";
  std::ofstream(stub) << R"(#!/usr/bin/env bash
[ "$1" = run ] || exit 9
shift 2
ms=1 label= log= fail= out=
while [ $# -gt 0 ]; do
  case $1 in
    --ms) ms=$2; shift;; --label) label=$2; shift;; --log) log=$2; shift;;
    --fail) fail=$2; shift;; --out) out=$2; shift;; --hang) exec sleep "$2";;
  esac
  shift
done
[ -n "$log" ] && printf '%s' "$label" >> "$log"
[ -n "$fail" ] && exit "$fail"
mkdir -p "$out"
g1=$(awk "BEGIN{print $ms * 1.01}") g2=$(awk "BEGIN{print $ms * 0.99}")
cat > "$out/report.json" <<JSON
{"tool": "aoreplay", "run": {"repeat": 3}, "gpu_ms_total_median": $(awk "BEGIN{print $ms + 1}"),
 "passes": [{"name": "gtao", "gpu_ms": {"samples": [$ms, $g1, $g2]}},
            {"name": "spatial", "gpu_ms": {"samples": [1, 1.01, 0.99]}}],
 "frames": [{"gpu_ms_median": {"gtao": $ms, "spatial": 1}}]}
JSON
)";
  fs::permissions(stub, fs::perms::owner_all);
  return stub;
}

struct AbSetup {
  fs::path dir, stub, log, out;
  std::string capture = generatedCapture("boxes", "orbit", 64, 36, 3).string();
  explicit AbSetup(const std::string& name)
      : dir(scratchDir(name)), stub(stubBinary(dir)), log(dir / "order.txt"), out(dir / "result") {}
  std::string command(int rounds, const std::string& aArgs, const std::string& bArgs, const std::string& extra = "") const {
    return fmt::format("ab {} --rounds {} --a-binary {} --b-binary {} --a '--label a --log {} {}' --b '--label b --log {} {}' --out {} {}",
                       capture, rounds, stub.string(), stub.string(), log.string(), aArgs, log.string(), bArgs,
                       out.string(), extra);
  }
};

TEST(Ab, RunsInAbbaOrderKeepsEveryRunAndFindsASlowerB) {
  AbSetup ab("ab-slower");
  auto junit = ab.dir / "ab-junit.xml";
  auto r = runAoreplay(ab.command(3, "--ms 1", "--ms 1.5", "--junit " + junit.string()));
  ASSERT_EQ(r.exitCode, 1) << r.output;
  EXPECT_EQ(readText(ab.log), "abbaabbaabba");
  // CI's view: one JUnit case per judged name, the slower one failed; the page beside compare.json.
  std::string xml = readText(junit);
  EXPECT_NE(xml.find(R"(<failure message="gtao is slower)"), std::string::npos) << xml;
  EXPECT_EQ(std::system(fmt::format("xmllint --noout '{}'", junit.string()).c_str()), 0) << xml;
  EXPECT_NE(readText(ab.out / "compare.html").find("<section id=\"distributions\">"), std::string::npos);
  for (int i = 1; i <= 6; ++i)
    for (const char* side : {"a", "b"})
      EXPECT_TRUE(fs::exists(ab.out / side / fmt::format("{:02d}", i) / "report.json")) << side << i;
  EXPECT_NE(r.output.find("ab: run 12/12 (round 3/3): a/06"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("values: one per run"), std::string::npos) << r.output;

  auto verdicts = readJsonFile(ab.out / "compare.json");
  EXPECT_EQ(verdicts["level"], "runs");
  EXPECT_EQ(verdicts["baseline"]["runs"], 6);
  EXPECT_EQ(verdicts["passes"][0]["name"], "gtao");
  EXPECT_EQ(verdicts["passes"][0]["verdict"], "slower");
  EXPECT_NEAR(verdicts["passes"][0]["ratio"].get<double>(), 1.5, 1e-9);
  EXPECT_EQ(verdicts["passes"][1]["verdict"], "same");
  auto record = readJsonFile(ab.out / "ab.json");
  ASSERT_EQ(record["runs"].size(), 12u);
  EXPECT_EQ(record["runs"][1]["out"], "b/01");
  EXPECT_EQ(record["runs"][3]["out"], "a/02");
  EXPECT_EQ(record["exit_status"], 1);

  // The same verdicts as `compare DIR/a DIR/b`, exit code included.
  auto again = ab.dir / "again.json";
  auto c = runAoreplay(fmt::format("compare {} {} --json {}", (ab.out / "a").string(), (ab.out / "b").string(), again.string()));
  EXPECT_EQ(c.exitCode, 1) << c.output;
  auto rejudged = readJsonFile(again);
  for (size_t i = 0; i < verdicts["passes"].size(); ++i) {
    EXPECT_EQ(rejudged["passes"][i]["verdict"], verdicts["passes"][i]["verdict"]) << i;
    EXPECT_EQ(rejudged["passes"][i]["p_holm"], verdicts["passes"][i]["p_holm"]) << i;
  }
}

TEST(Ab, SameTimesAreSameAndAnEarlierResultIsReplaced) {
  AbSetup ab("ab-same");
  auto r = runAoreplay(ab.command(3, "--ms 1", "--ms 1"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const auto& p : readJsonFile(ab.out / "compare.json")["passes"]) EXPECT_EQ(p["verdict"], "same") << p["name"];
  // DIR holds ab.json: an earlier result, replaced by the next one.
  r = runAoreplay(ab.command(1, "--ms 1", "--ms 1"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_FALSE(fs::exists(ab.out / "a" / "03")) << "the earlier result's runs are gone";
}

TEST(Ab, TooFewRoundsAreUnknownAndFailOnlyWhenAsked) {
  AbSetup ab("ab-unknown");
  auto r = runAoreplay(ab.command(1, "--ms 1", "--ms 1.5"));
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("unknown — need 3 more runs a side"), std::string::npos) << r.output;
  r = runAoreplay(ab.command(1, "--ms 1", "--ms 1.5", "--fail-on-unknown"));
  EXPECT_EQ(r.exitCode, 1) << r.output;
}

TEST(Ab, AFailedRunStopsItAndLeavesNothing) {
  AbSetup ab("ab-failed");
  auto r = runAoreplay(ab.command(2, "--ms 1", "--fail 2"));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_EQ(readText(ab.log), "ab") << "stopped at the first failure";
  EXPECT_NE(r.output.find("b/01 failed"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(ab.out));
  for (const auto& entry : fs::directory_iterator(ab.dir))
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
  r = runAoreplay(ab.command(1, "--ms 1", "--fail 1"));
  EXPECT_EQ(r.exitCode, 1) << r.output;
}

// A run that hangs is killed past --run-timeout and fails ab; a signal that ends ab ends its run
// too (the run took signals blocked, as aoreplay's main thread holds them, and outlived ab).
TEST(Ab, AHungRunIsKilledAndARunEndsWithAb) {
  AbSetup ab("ab-hung");
  auto r = runAoreplay(ab.command(1, "--hang 61.25", "--ms 1", "--run-timeout 1"));
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("a/01 ran past --run-timeout 1"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(ab.out));
  // "[s]" keeps the pattern from matching the shell that runs pgrep.
  EXPECT_NE(std::system("pgrep -f '[s]leep 61.25' >/dev/null"), 0) << "the hung run was left running";

  const std::string background = fmt::format("{} {} > {} 2>&1 & echo $! > {}", AOR_EXE, ab.command(1, "--hang 62.5", "--ms 1"),
                                             (ab.dir / "ab.log").string(), (ab.dir / "ab.pid").string());
  ASSERT_EQ(std::system(background.c_str()), 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  ASSERT_EQ(std::system("pgrep -f '[s]leep 62.5' >/dev/null"), 0) << "the run should be going";
  ASSERT_EQ(std::system(fmt::format("kill -TERM $(cat {})", (ab.dir / "ab.pid").string()).c_str()), 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(1000));
  EXPECT_NE(std::system("pgrep -f '[s]leep 62.5' >/dev/null"), 0) << "the run outlived ab";
  EXPECT_FALSE(fs::exists(ab.out));
}

TEST(Ab, BadArgumentsAreRefusedBeforeAnyRun) {
  AbSetup ab("ab-bad");
  auto refused = [&](const std::string& command, const std::string& message) {
    auto r = runAoreplay(command);
    EXPECT_EQ(r.exitCode, 2) << command << "\n" << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << command << "\n" << r.output;
    EXPECT_FALSE(fs::exists(ab.log)) << "no run started: " << command;
  };
  refused(ab.command(1, "--out elsewhere", ""), "ab chooses every run's output folder");
  refused(ab.command(1, "", "--out=elsewhere"), "--b");
  refused(ab.command(1, "$(touch x)", ""), "command substitution");
  refused(fmt::format("ab {} --rounds 1 --a-binary {}", ab.capture, (ab.dir / "nope").string()), "is not an executable file");
  refused(fmt::format("ab {} --rounds 1", (ab.dir / "no-capture").string()), "capture folder does not exist");
  refused(fmt::format("ab {} --rounds 0", ab.capture), "--rounds");
  fs::create_directories(ab.out);
  std::ofstream(ab.out / "precious.txt") << "keep";
  refused(ab.command(1, "", ""), "which aoreplay did not write there");
  EXPECT_TRUE(fs::exists(ab.out / "precious.txt"));
}

TEST(Ab, TheRealBinaryRunsBothSidesAsFreshProcesses) {
  auto dir = scratchDir("ab-real");
  auto capture = generatedCapture("boxes", "orbit", 64, 36, 3);
  auto out = dir / "result";
  auto r = runAoreplay(fmt::format("ab {} --rounds 1 --a '--frames 0:2 --no-images --validate' "
                                   "--b '--frames 0:2 --no-images --validate --set slices=4' --out {}",
                                   capture.string(), out.string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;  // 2 runs a side cannot give a verdict
  auto record = readJsonFile(out / "ab.json");
  EXPECT_EQ(record["a"]["binary"], record["b"]["binary"]) << "both default to this binary";
  EXPECT_EQ(fs::canonical(record["a"]["binary"].get<std::string>()), fs::canonical(AOR_EXE));
  for (const char* run : {"a/01", "a/02", "b/01", "b/02"}) {
    auto report = readJsonFile(out / run / "report.json");
    EXPECT_EQ(report["validation"]["messages"], 0) << run;
    EXPECT_EQ(report["settings"]["slices"], run[0] == 'a' ? 3 : 4) << run;
    auto timings = loadTimingSamples(out / run / "report.json");
    EXPECT_EQ(timings.back().name, "total");
    EXPECT_EQ(timings.back().runValue(), report["gpu_ms_total_median"].get<double>()) << run;
  }
  EXPECT_NE(r.output.find("(2 runs)"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace aor::test
