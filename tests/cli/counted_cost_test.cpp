// `run --cost instructions|cycles`: the same counts for every pass in separate processes, more work
// counted as more, compare judging counts exactly, and the refusals. Each counted run re-executes
// aoreplay under valgrind's callgrind (a few seconds for a 1-frame 64x36 capture).
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "gpu_test_support.h"
#include "scratch_folder.h"

namespace aor::test {
namespace {
namespace fs = std::filesystem;

fs::path pathOf(const std::string& name) { return processScratchFolder("aor_cost") / name; }

// A fresh output folder (nothing left from an earlier test).
fs::path outDir(const std::string& name) {
  fs::path dir = pathOf(name);
  fs::remove_all(dir);
  return dir;
}

std::string capture() { return generatedCapture("boxes", "orbit", 64, 36, 2).string(); }

// One counted run: its report.json (the test fails when the run does).
nlohmann::json countedRun(const std::string& name, const std::string& extra, const std::string& measure = "instructions") {
  fs::path out = outDir(name);
  auto r = runAoreplay("run " + capture() + " --frames 0:1 --no-images --cost " + measure + " --out " + out.string() + " " + extra);
  EXPECT_EQ(r.exitCode, 0) << r.output;
  return r.exitCode == 0 ? readJsonFile(out / "report.json") : nlohmann::json::object();
}

TEST(CountedCost, TwoProcessesCountEveryPassIdentically) {
  auto a = countedRun("same_a", ""), b = countedRun("same_b", "");
  ASSERT_TRUE(a.contains("frames") && b.contains("frames"));
  const auto& fa = a["frames"][0]["instructions"];
  const auto& fb = b["frames"][0]["instructions"];
  ASSERT_GE(fa.size(), 4u) << fa.dump();
  EXPECT_EQ(fa, fb);
  double compute = 0;
  for (const auto& [pass, value] : fa.items()) {
    EXPECT_GT(value.get<double>(), 1000.0) << pass;
    if (pass != "upload" && pass != "readback") compute += value.get<double>();
  }
  EXPECT_EQ(a["instructions_total"].get<double>(), compute);
  EXPECT_FALSE(a.contains("gpu_ms_total_median"));
  EXPECT_EQ(a["cost"]["measure"], "instructions");
  EXPECT_EQ(a["cost"]["key"], b["cost"]["key"]);
  EXPECT_NE(a["cost"]["valgrind"].get<std::string>().find("valgrind"), std::string::npos) << a["cost"].dump();
}

TEST(CountedCost, MoreSlicesCountMoreInGtaoAloneAndCompareSaysSo) {
  fs::path one = outDir("slices1"), two = outDir("slices2");
  for (auto [out, slices] : {std::pair{one, 1}, std::pair{two, 2}}) {
    auto r = runAoreplay("run " + capture() + " --frames 0:1 --no-images --cost instructions --set slices=" +
                         std::to_string(slices) + " --out " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
  }
  auto a = readJsonFile(one / "report.json")["frames"][0]["instructions"];
  auto b = readJsonFile(two / "report.json")["frames"][0]["instructions"];
  EXPECT_GT(b["gtao"].get<double>(), 1.3 * a["gtao"].get<double>());
  EXPECT_EQ(a["linearize_depth"], b["linearize_depth"]);  // its inputs are byte-identical
  EXPECT_EQ(a["upload"], b["upload"]);
  const fs::path json = pathOf("slices.compare.json");
  auto compare = runAoreplay("compare " + (one / "report.json").string() + " " + (two / "report.json").string() +
                             " --json " + json.string());
  EXPECT_EQ(compare.exitCode, 1) << compare.output;
  auto verdicts = readJsonFile(json);
  EXPECT_EQ(verdicts["measure"], "instructions");
  EXPECT_EQ(verdicts["level"], "counts");
  for (const auto& p : verdicts["passes"]) {
    if (p["name"] == "gtao") {
      EXPECT_EQ(p["verdict"], "slower");
    }
    if (p["name"] == "linearize_depth") {
      EXPECT_EQ(p["verdict"], "same");
    }
  }
}

TEST(CountedCost, CyclesPinTheCacheAndExceedInstructions) {
  auto instructions = countedRun("cyc_i", "");
  auto cycles = countedRun("cyc_c", "", "cycles");
  ASSERT_TRUE(cycles.contains("cost"));
  EXPECT_EQ(cycles["cost"]["cache"]["LL"], "8388608,16,64");
  EXPECT_TRUE(cycles["cost"].contains("formula"));
  EXPECT_GT(cycles["cycles_total"].get<double>(), instructions["instructions_total"].get<double>());
  EXPECT_NE(cycles["cost"]["key"], instructions["cost"]["key"]);
}

TEST(CountedCost, OptionsThatMakeNoSenseWithCountsAreRefused) {
  const std::string base = "run " + capture() + " --frames 0:1 --no-images --cost instructions --out " + outDir("refused").string();
  for (const std::string extra : {"--repeat 2", "--overlap", "--validate"}) {
    auto r = runAoreplay(base + " " + extra);
    EXPECT_EQ(r.exitCode, 2) << extra << "\n" << r.output;
    EXPECT_NE(r.output.find(extra.substr(0, extra.find(' '))), std::string::npos) << r.output;
  }
  EXPECT_FALSE(fs::exists(outDir("refused")));
  auto missing = runAoreplay(base, "PATH=/nonexistent");
  EXPECT_EQ(missing.exitCode, 2) << missing.output;
  EXPECT_NE(missing.output.find("apt-get install valgrind"), std::string::npos) << missing.output;
}

TEST(CountedCost, TimeThresholdsAndTimedComparisonsDoNotApplyToCounts) {
  fs::path counted = outDir("expect_counted");
  fs::path expect = outDir("expect") += ".json";
  fs::create_directories(expect.parent_path());
  std::ofstream(expect) << R"({"max": {"gpu_ms.gtao": 5}})";
  auto r = runAoreplay("run " + capture() + " --frames 0:1 --no-images --cost instructions --expect " + expect.string() +
                       " --out " + counted.string());
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("gpu_ms.gtao"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(counted));

  fs::path timed = outDir("timed");
  ASSERT_EQ(runAoreplay("run " + capture() + " --frames 0:1 --no-images --out " + timed.string()).exitCode, 0);
  countedRun("for_compare", "");
  fs::path countedReport = pathOf("for_compare") / "report.json";
  auto mixed = runAoreplay("compare " + (timed / "report.json").string() + " " + countedReport.string());
  EXPECT_EQ(mixed.exitCode, 2) << mixed.output;
  EXPECT_NE(mixed.output.find("one measure"), std::string::npos) << mixed.output;
  auto alpha = runAoreplay("compare " + countedReport.string() + " " + countedReport.string() + " --alpha 0.01");
  EXPECT_EQ(alpha.exitCode, 2) << alpha.output;
  EXPECT_NE(alpha.output.find("--alpha is for timed runs"), std::string::npos) << alpha.output;
}

TEST(CountedCost, SweepCountsEachConfigurationsPasses) {
  fs::path out = outDir("sweep");
  auto r = runAoreplay("sweep " + capture() + " --frames 0:1 --cost instructions --presets high --grid slices=1,2 --out " +
                       out.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("instructions counted under callgrind"), std::string::npos) << r.output;
  auto sweep = readJsonFile(out / "sweep.json");
  ASSERT_EQ(sweep["rows"].size(), 2u);
  const auto& one = sweep["rows"][0]["instructions"];
  const auto& two = sweep["rows"][1]["instructions"];
  EXPECT_GT(two["gtao"].get<double>(), 1.3 * one["gtao"].get<double>());
  // One process counts the configurations one after another: a pass that did not change counts the
  // same within a few instructions (its pipelines and buffers lie elsewhere), not exactly.
  EXPECT_NEAR(one["linearize_depth"].get<double>(), two["linearize_depth"].get<double>(),
              1e-4 * one["linearize_depth"].get<double>());
  EXPECT_FALSE(sweep["rows"][0].contains("gpu_ms_total"));
  std::ifstream csv(out / "sweep.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_NE(header.find("gtao_instructions"), std::string::npos) << header;
  EXPECT_NE(header.find("total_instructions"), std::string::npos) << header;
  EXPECT_EQ(header.find("_ms"), std::string::npos) << header;
}

}  // namespace
}  // namespace aor::test
