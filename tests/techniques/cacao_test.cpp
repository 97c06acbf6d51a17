// FidelityFX CACAO (seed 001, --technique cacao): each of the ten configurations (five quality
// levels, native or downsampled) runs exactly the passes of the seed's pass table, in its order,
// with and without the capture's normals, validation-clean and bit-identical twice; `graph` draws
// each; the adaptive pass spends its extra taps where the importance map is high. The generic
// checks (presets validated, LP_NUM_THREADS, the stress suite, keys) are technique_coverage_test.cpp's
// and stress_test.cpp's.
#include <array>
#include <cctype>
#include <filesystem>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "gpu_test_support.h"

namespace aor::test {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

fs::path shipped(const std::string& name) { return fs::path(AOR_SOURCE_DIR) / "captures" / name; }

constexpr std::array<const char*, 5> kLevels = {"lowest", "low", "medium", "high", "highest"};

// The seed's pass table (seed 001, "which passes of the FidelityFX CACAO algorithm are present in
// the different configurations", with its entry-point tables), written out as data: each row is
// one step in the seed's order and names, per level, the entry point that runs in it ("" where the
// table has a cross). `{res}` is Native or Downsampled; `{normals}` is Normals when normals are
// generated from depth and NormalsFromInputNormals otherwise.
struct SeedRow {
  std::array<const char*, 5> native;       // lowest, low, medium, high, highest
  std::array<const char*, 5> downsampled;
};
const std::vector<SeedRow> kSeedTable = {
    // clear load counter
    {{"ClearLoadCounter", "ClearLoadCounter", "ClearLoadCounter", "ClearLoadCounter", "ClearLoadCounter"},
     {"ClearLoadCounter", "ClearLoadCounter", "ClearLoadCounter", "ClearLoadCounter", "ClearLoadCounter"}},
    // prepare depths (DepthsHalf at lowest, Depths at low, DepthsAndMips from medium)
    {{"PrepareNativeDepthsHalf", "PrepareNativeDepths", "PrepareNativeDepthsAndMips", "PrepareNativeDepthsAndMips",
      "PrepareNativeDepthsAndMips"},
     {"PrepareDownsampledDepthsHalf", "PrepareDownsampledDepths", "PrepareDownsampledDepthsAndMips",
      "PrepareDownsampledDepthsAndMips", "PrepareDownsampledDepthsAndMips"}},
    // prepare normals
    {{"Prepare{res}{normals}", "Prepare{res}{normals}", "Prepare{res}{normals}", "Prepare{res}{normals}", "Prepare{res}{normals}"},
     {"Prepare{res}{normals}", "Prepare{res}{normals}", "Prepare{res}{normals}", "Prepare{res}{normals}", "Prepare{res}{normals}"}},
    // adaptive: base pass, importance map, its two postprocess passes (highest only)
    {{"", "", "", "", "GenerateQ3Base"}, {"", "", "", "", "GenerateQ3Base"}},
    {{"", "", "", "", "GenerateImportanceMap"}, {"", "", "", "", "GenerateImportanceMap"}},
    {{"", "", "", "", "PostprocessImportanceMapA"}, {"", "", "", "", "PostprocessImportanceMapA"}},
    {{"", "", "", "", "PostprocessImportanceMapB"}, {"", "", "", "", "PostprocessImportanceMapB"}},
    // generate SSAO
    {{"GenerateQ0", "GenerateQ0", "GenerateQ1", "GenerateQ2", "GenerateQ3"},
     {"GenerateQ0", "GenerateQ0", "GenerateQ1", "GenerateQ2", "GenerateQ3"}},
    // edge-sensitive blur (blurPassCount > 0; its N is the pass count, not in the pass's name)
    {{"EdgeSensitiveBlur", "EdgeSensitiveBlur", "EdgeSensitiveBlur", "EdgeSensitiveBlur", "EdgeSensitiveBlur"},
     {"EdgeSensitiveBlur", "EdgeSensitiveBlur", "EdgeSensitiveBlur", "EdgeSensitiveBlur", "EdgeSensitiveBlur"}},
    // apply (native) or bilateral upsample (downsampled)
    {{"NonSmartHalfApply", "NonSmartApply", "Apply", "Apply", "Apply"},
     {"UpscaleBilateral5x5Half", "UpscaleBilateral5x5NonSmart", "UpscaleBilateral5x5NonSmart", "UpscaleBilateral5x5Smart",
      "UpscaleBilateral5x5Smart"}},
};

// FFX_CACAO_ + an entry point's CamelCase as the graph names it: cacao_ + snake_case, "5x5" one word.
std::string graphName(std::string entry) {
  std::string out = "cacao";
  for (size_t i = 0; i < entry.size(); ++i) {
    if (entry.compare(i, 3, "5x5") == 0) {
      out += "_5x5";
      i += 2;
      continue;
    }
    char ch = entry[i];
    if (std::isupper(static_cast<unsigned char>(ch))) {
      out += '_';
      out += char(std::tolower(static_cast<unsigned char>(ch)));
    } else {
      out += ch;
    }
  }
  return out;
}

std::vector<std::string> expectedPasses(int level, bool downsampled, bool generatedNormals) {
  std::vector<std::string> passes;
  for (const auto& row : kSeedTable) {
    std::string entry = (downsampled ? row.downsampled : row.native)[size_t(level)];
    if (entry.empty()) continue;
    entry = fmt::format(fmt::runtime(entry), fmt::arg("res", downsampled ? "Downsampled" : "Native"),
                        fmt::arg("normals", generatedNormals ? "Normals" : "NormalsFromInputNormals"));
    passes.push_back(graphName(entry));
  }
  return passes;
}

std::vector<std::string> cacaoPassesOf(const json& list) {
  std::vector<std::string> names;
  for (const auto& p : list) {
    std::string name = p["name"];
    if (name.rfind("cacao_", 0) == 0) names.push_back(name);
  }
  return names;
}

struct Configuration {
  int level = 3;
  bool downsampled = false;
  std::string label() const { return fmt::format("{} downsample={}", kLevels[size_t(level)], int(downsampled)); }
  std::string options() const { return fmt::format("--technique cacao --preset {} --set downsample={}", kLevels[size_t(level)], int(downsampled)); }
};

std::vector<Configuration> everyConfiguration() {
  std::vector<Configuration> all;
  for (int level = 0; level < 5; ++level)
    for (bool downsampled : {false, true}) all.push_back({level, downsampled});
  return all;
}

// A capture with normals (shipped) and one without (generated depth-only): normals from the
// capture's, then from depth.
struct CaptureCase {
  fs::path path;
  bool generatesNormals;
};
std::vector<CaptureCase> bothCaptures() {
  return {{shipped("boxes-static"), false}, {generatedCapture("boxes", "orbit", 160, 90, 1, false), true}};
}

TEST(CacaoSeedTable, TheTableGivesTheEntryPointsOfTheSeedsPrepareTable) {
  // The seed's entry-point table for prepare depths, read through the pass table's rows.
  EXPECT_EQ(expectedPasses(0, false, true)[1], "cacao_prepare_native_depths_half");
  EXPECT_EQ(expectedPasses(1, true, true)[1], "cacao_prepare_downsampled_depths");
  EXPECT_EQ(expectedPasses(2, false, false)[1], "cacao_prepare_native_depths_and_mips");
  EXPECT_EQ(expectedPasses(4, true, false)[2], "cacao_prepare_downsampled_normals_from_input_normals");
  EXPECT_EQ(expectedPasses(4, true, true).back(), "cacao_upscale_bilateral_5x5_smart");
  EXPECT_EQ(expectedPasses(4, false, true).size(), 10u);
  EXPECT_EQ(expectedPasses(3, false, true).size(), 6u);
}

// Every configuration, with and without the capture's normals: report.json's passes are exactly
// the table's, in its order, none culled, and validation (synchronisation included) says nothing.
TEST(Cacao, EveryConfigurationRunsExactlyTheSeedTablesPassesValidationClean) {
  for (const auto& capture : bothCaptures())
    for (const auto& c : everyConfiguration()) {
      std::string label = c.label() + (capture.generatesNormals ? " depth-only" : " with normals");
      fs::path out = scratchDir("cacao-passes") / "out";
      auto r = runAoreplay(fmt::format("run {} {} --frames 0:1 --validate --no-images --out {}", capture.path.string(),
                                       c.options(), out.string()));
      ASSERT_EQ(r.exitCode, 0) << label << "\n" << r.output;
      EXPECT_NE(r.output.find("validation: 0 messages"), std::string::npos) << label << "\n" << r.output;
      json report = json::parse(readText(out / "report.json"));
      EXPECT_EQ(cacaoPassesOf(report["passes"]), expectedPasses(c.level, c.downsampled, capture.generatesNormals)) << label;
      EXPECT_TRUE(cacaoPassesOf(report["culled_passes"]).empty()) << label << ": " << report["culled_passes"].dump();
    }
}

// generate_normals=1 on a capture with normals takes the from-depth entry point, and no blur pass
// runs at blur_pass_count=0 (the blur row's cross).
TEST(Cacao, GenerateNormalsAndNoBlurChangeOnlyTheirRows) {
  fs::path out = scratchDir("cacao-options") / "out";
  auto r = runAoreplay(fmt::format("run {} --technique cacao --preset highest --set generate_normals=1 --set blur_pass_count=0 "
                                   "--frames 0:1 --validate --no-images --out {}",
                                   shipped("boxes-static").string(), out.string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("validation: 0 messages"), std::string::npos) << r.output;
  auto expected = expectedPasses(4, false, true);
  std::erase(expected, "cacao_edge_sensitive_blur");
  EXPECT_EQ(cacaoPassesOf(json::parse(readText(out / "report.json"))["passes"]), expected);
}

// The importance map exists only at highest: asking for it at high is an error, not an empty folder.
TEST(Cacao, ADebugViewTheLevelDoesNotWriteIsAnError) {
  fs::path out = scratchDir("cacao-missing-view") / "out";
  auto r = runAoreplay(fmt::format("run {} --technique cacao --preset high --frames 0:1 --debug importance_map --out {}",
                                   shipped("boxes-static").string(), out.string()));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("writes no debug view 'importance_map'"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\"quality\":\"high\""), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out / "report.json"));
}

TEST(Cacao, GraphDrawsEveryConfiguration) {
  for (const auto& c : everyConfiguration()) {
    fs::path dot = scratchDir("cacao-graph") / "graph.dot";
    auto r = runAoreplay(fmt::format("graph {} {} --frames 0:1 --dot {}", shipped("boxes-static").string(), c.options(), dot.string()));
    ASSERT_EQ(r.exitCode, 0) << c.label() << "\n" << r.output;
    std::string text = readText(dot);
    for (const auto& pass : expectedPasses(c.level, c.downsampled, false))
      EXPECT_NE(text.find(pass), std::string::npos) << c.label() << ": " << pass << " not drawn";
  }
}

TEST(Cacao, EveryConfigurationReplaysBitIdenticallyTwice) {
  for (const auto& capture : bothCaptures())
    for (const auto& c : everyConfiguration()) {
      std::vector<std::string> settings{fmt::format("quality={}", kLevels[size_t(c.level)]),
                                        fmt::format("downsample={}", int(c.downsampled))};
      auto first = replayWithSettings(capture.path, "cacao", settings, 0, 1);
      auto second = replayWithSettings(capture.path, "cacao", settings, 0, 1);
      ASSERT_EQ(first.frames.size(), 1u);
      ASSERT_EQ(second.frames.size(), 1u);
      EXPECT_TRUE(bitIdentical(first.frames[0].visibility, second.frames[0].visibility)) << c.label();
      // Not all lit: the boxes occlude the floor.
      double sum = 0;
      for (float v : first.frames[0].visibility) sum += v;
      EXPECT_LT(sum / double(first.frames[0].visibility.size()), 0.99) << c.label();
    }
}

// At highest, the adaptive pass's extra taps go where the importance map is high: the counting
// build's mean extra taps per pixel where importance >= 0.5 against below it.
TEST(Cacao, AdaptiveTapsAreSpentWhereTheImportanceMapIsHigh) {
  fs::path out = scratchDir("cacao-adaptive") / "out";
  auto r = runAoreplay(fmt::format("run {} --technique cacao --preset highest --frames 0:1 --debug adaptive_taps "
                                   "--debug importance_map --out {}",
                                   shipped("boxes-static").string(), out.string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  json taps = json::parse(readText(out / "report.json"))["frames"][0]["debug"]["adaptive_taps"];
  ASSERT_EQ(taps.size(), 4u) << taps.dump();
  double insidePixels = taps[1].get<double>(), outsidePixels = taps[3].get<double>();
  ASSERT_GT(insidePixels, 0.0) << taps.dump();
  ASSERT_GT(outsidePixels, 0.0) << taps.dump();
  double inside = taps[0].get<double>() / insidePixels, outside = taps[2].get<double>() / outsidePixels;
  std::cout << fmt::format("cacao highest, boxes-static: mean extra taps {:.2f} where importance >= 0.5 ({} pixels), "
                           "{:.2f} below ({} pixels)\n",
                           inside, insidePixels, outside, outsidePixels);
  // Every pixel of the four layers (80 x 45 each) is counted once.
  EXPECT_EQ(insidePixels + outsidePixels, 4.0 * 80 * 45);
  EXPECT_GT(inside, 2.0 * outside) << taps.dump();
  EXPECT_TRUE(fs::exists(out / "debug" / "importance_map" / "0000.png"));
}

TEST(Cacao, EveryDebugViewIsWrittenAtHighestAndLowest) {
  const Technique& t = findTechnique("cacao");
  for (const char* preset : {"highest", "lowest"}) {
    std::string views;
    bool highest = std::string(preset) == "highest";
    for (const auto& v : t.debugViews)
      if (highest || (v.name != "importance_map" && v.name != "adaptive_taps")) views += " --debug " + v.name;
    fs::path out = scratchDir("cacao-debug") / "out";
    auto r = runAoreplay(fmt::format("run {} --technique cacao --preset {} --frames 0:1{} --validate --out {}",
                                     shipped("boxes-static").string(), preset, views, out.string()));
    ASSERT_EQ(r.exitCode, 0) << preset << "\n" << r.output;
    EXPECT_NE(r.output.find("validation: 0 messages"), std::string::npos) << preset << "\n" << r.output;
    for (const auto& v : t.debugViews) {
      if (v.name == "adaptive_taps" || (!highest && v.name == "importance_map")) continue;
      EXPECT_TRUE(fs::exists(out / "debug" / v.name / "0000.png")) << preset << " " << v.name;
    }
  }
}

}  // namespace
}  // namespace aor::test
