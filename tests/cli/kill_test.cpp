// Issue 20, point 8: a kill at any moment of a run that replaces an earlier result leaves --out
// holding a complete result (the old one or the new one), or, between the two renames of the
// fallback swap, leaves the old one aside for the next run to put back; after one more run no
// staging folder or lock file is left. The test-only switch AOREPLAY_TEST_KILL_AFTER=STEP makes
// aoreplay SIGKILL itself right after STEP (core/output_directory.cpp); AOREPLAY_TEST_NO_EXCHANGE=1
// takes the path of file systems without RENAME_EXCHANGE. Then 50 kills at random moments.
#include <chrono>
#include <cstdio>
#include <random>
#include <thread>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "output_test_support.h"

namespace aor::test {
namespace {

namespace fs = std::filesystem;

fs::path capture() { return generatedCapture("boxes", "orbit", 32, 18, 2); }

std::vector<std::string> runArgs(const fs::path& out, int frames) {
  return {"run", capture().string(), "--out", out.string(), "--frames", fmt::format("0:{}", frames)};
}

int runToEnd(const fs::path& out, int frames, const std::vector<std::string>& environment = {}) {
  return waitFor(spawnAoreplay(runArgs(out, frames), environment));
}

// Names beside the result other than the result itself: staging folders, asides, locks.
std::set<std::string> strays(const fs::path& dir) {
  auto names = namesIn(dir);
  names.erase("result");
  return names;
}

struct Step {
  const char* name;
  bool fallback;  // AOREPLAY_TEST_NO_EXCHANGE=1
};

class KillAfterStep : public ::testing::TestWithParam<Step> {};

TEST_P(KillAfterStep, LeavesTheOldOrTheNewResultAndTheNextRunCleansUp) {
  const Step step = GetParam();
  auto dir = scratchDir("step");
  auto out = dir / "result";
  ASSERT_EQ(runToEnd(out, 1), 0) << "the earlier result, of one frame";
  std::vector<std::string> environment = {fmt::format("AOREPLAY_TEST_KILL_AFTER={}", step.name)};
  if (step.fallback) environment.push_back("AOREPLAY_TEST_NO_EXCHANGE=1");

  const int killed = runToEnd(out, 2, environment);
  ASSERT_TRUE(WIFSIGNALED(killed) && WTERMSIG(killed) == SIGKILL) << "the switch did not fire at " << step.name;
  const size_t frames = completeRunFrames(out);
  if (std::string(step.name) == "moved-aside") {
    // Between the fallback's two renames NAME is missing, the complete old result aside.
    EXPECT_FALSE(fs::exists(out));
    bool aside = false;
    for (const auto& name : namesIn(dir)) aside |= name.rfind(".result.old-", 0) == 0 && completeRunFrames(dir / name) == 1;
    EXPECT_TRUE(aside) << "the old result is not aside";
  } else {
    EXPECT_TRUE(frames == 1 || frames == 2) << "after a kill at " << step.name << " --out is neither result";
  }
  const bool newInPlace = frames == 2;

  // The next run takes the lock and repairs first: stopped right there, it shows the repair alone.
  const int repaired = runToEnd(out, 2, {"AOREPLAY_TEST_KILL_AFTER=recovered"});
  ASSERT_TRUE(WIFSIGNALED(repaired));
  EXPECT_EQ(completeRunFrames(out), newInPlace ? 2u : 1u) << "the repair after " << step.name;
  for (const auto& name : strays(dir)) EXPECT_EQ(name, ".result.lock") << "left after the repair";

  ASSERT_EQ(runToEnd(out, 2), 0);
  EXPECT_EQ(completeRunFrames(out), 2u);
  EXPECT_EQ(strays(dir), std::set<std::string>{}) << "after one more run";
}

INSTANTIATE_TEST_SUITE_P(
    EveryStep, KillAfterStep,
    ::testing::Values(Step{"locked", false}, Step{"recovered", false}, Step{"staged", false}, Step{"marked", false},
                      Step{"exchanged", false}, Step{"old-removed-partly", false}, Step{"old-removed", false},
                      Step{"unlocked", false}, Step{"marked", true}, Step{"moved-aside", true}, Step{"moved-in", true},
                      Step{"old-removed-partly", true}, Step{"old-removed", true}),
    [](const ::testing::TestParamInfo<Step>& info) {
      std::string name = std::string(info.param.fallback ? "fallback_" : "exchange_") + info.param.name;
      std::replace(name.begin(), name.end(), '-', '_');
      return name;
    });

TEST(KillAtRandomMoments, FiftyKillsAndTermsNeverLeaveABrokenResult) {
  auto dir = scratchDir("random");
  auto out = dir / "result";
  ASSERT_EQ(runToEnd(out, 1), 0);
  // How long a whole run takes here: the kills are spread over that.
  const auto start = std::chrono::steady_clock::now();
  ASSERT_EQ(runToEnd(out, 2), 0);
  const double runMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  std::mt19937 random(20);  // fixed: the same moments every time, on the same machine
  std::uniform_real_distribution<double> moment(0.0, runMs);
  int interrupted = 0;
  for (int i = 0; i < 50; ++i) {
    const int signal = i % 2 ? SIGTERM : SIGKILL;
    const pid_t pid = spawnAoreplay(runArgs(out, 1 + i % 2));
    ASSERT_GT(pid, 0);
    std::this_thread::sleep_for(std::chrono::duration<double, std::milli>(moment(random)));
    kill(pid, signal);
    const int status = waitFor(pid);
    const bool signalled = WIFSIGNALED(status);
    interrupted += signalled;
    if (!signalled) {
      EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "kill " << i;
    }
    const size_t frames = completeRunFrames(out);
    EXPECT_TRUE(frames == 1 || frames == 2) << "kill " << i << " (signal " << signal << ") broke --out";
    // SIGTERM is handled: the run removes its lock (and its staging folder, which a writer thread
    // may still recreate in the instant before the process ends: the next run removes that).
    if (signal == SIGTERM) {
      EXPECT_EQ(strays(dir).count(".result.lock"), 0u) << "after SIGTERM " << i;
    }
    ASSERT_EQ(runToEnd(out, 2), 0) << "the run after kill " << i;
    EXPECT_EQ(completeRunFrames(out), 2u);
    EXPECT_EQ(strays(dir), std::set<std::string>{}) << "after the run that followed kill " << i;
  }
  std::printf("    %d of 50 signals arrived before the run ended\n", interrupted);
  // The signals fall over the whole run; far fewer arriving in time would mean the test no longer
  // interrupts anything.
  EXPECT_GE(interrupted, 10) << "too few signals arrived before the run ended";
}

}  // namespace
}  // namespace aor::test
