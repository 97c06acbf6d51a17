// Every registered technique through the CLI as users run it: each preset validated (Khronos
// validation with synchronization validation, zero messages), outputs bit-identical whatever
// LP_NUM_THREADS says, and its keys in every place that lists them (`techniques --json`, --help,
// report.json, sweep.csv), each checked against a list written here by hand, not read from the
// declarations the tool prints. A technique registered later is covered by registering it.
#include <filesystem>
#include <fstream>
#include <set>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "gpu_test_support.h"

namespace aor::test {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

fs::path shipped(const std::string& name) { return fs::path(AOR_SOURCE_DIR) / "captures" / name; }

// Every built-in by name and every shipped example user technique by its file.
std::vector<std::string> techniqueNames() { return coveredTechniques(); }

class EveryTechnique : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryTechnique, EveryPresetRunsWithValidationClean) {
  const Technique& t = findTechnique(GetParam());
  std::vector<std::string> presets;
  for (const auto& p : t.presets) presets.push_back(p.name);
  if (presets.empty()) presets.push_back("");
  for (const auto& preset : presets) {
    fs::path out = scratchDir("validate-" + t.name + "-" + preset) / "out";
    auto r = runAoreplay(fmt::format("run {} --technique {} {} --frames 0:3 --validate --no-images --out {}",
                                     shipped("boxes-strafe").string(), GetParam(), preset.empty() ? "" : "--preset " + preset,
                                     out.string()));
    EXPECT_EQ(r.exitCode, 0) << t.name << " " << preset << "\n" << r.output;
    EXPECT_NE(r.output.find("validation: 0 messages"), std::string::npos) << t.name << " " << preset << "\n" << r.output;
  }
}

TEST_P(EveryTechnique, OutputsAreBitIdenticalWhateverTheLavapipeThreadCount) {
  const Technique& t = findTechnique(GetParam());
  auto runWith = [&](int threads) {
    fs::path out = scratchDir(fmt::format("threads-{}-{}", t.name, threads)) / "out";
    auto r = runAoreplay(fmt::format("run {} --technique {} --frames 0:3 --out {}", shipped("boxes-strafe").string(), GetParam(),
                                     out.string()),
                         fmt::format("LP_NUM_THREADS={}", threads));
    EXPECT_EQ(r.exitCode, 0) << r.output;
    return out;
  };
  fs::path one = runWith(1), four = runWith(4);
  int compared = 0;
  for (const auto& entry : fs::directory_iterator(one / "ao")) {
    if (entry.path().extension() != ".exr") continue;
    EXPECT_EQ(readText(entry.path()), readText(four / "ao" / entry.path().filename())) << t.name << " " << entry.path();
    ++compared;
  }
  EXPECT_EQ(compared, 3);
}

INSTANTIATE_TEST_SUITE_P(Registered, EveryTechnique, ::testing::ValuesIn(techniqueNames()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return techniqueTestName(info.param); });

// The keys each technique must show, written by hand: a key dropped from the declarations, or a
// place that lists keys from a list of its own, fails here.
const std::map<std::string, std::vector<std::string>> kExpectedKeys = {
    {"gtao", {"radius", "slices", "steps", "falloff", "power", "thin", "spatial", "temporal", "bent", "half_res"}},
    {"reference", {"radius", "falloff", "power", "thin", "bent"}},
    {"xegtao", {"radius", "slices", "steps", "radius_multiplier", "falloff_range", "sample_distribution_power",
                "thin_occluder_compensation", "final_value_power", "depth_mip_sampling_offset", "denoise_passes", "depth32",
                "bent", "temporal"}},
    {"vbao", {"radius", "slices", "steps", "thickness", "sectors", "weighting", "radius_multiplier", "falloff_range",
              "sample_distribution_power", "final_value_power", "depth_mip_sampling_offset", "denoise_passes", "depth32",
              "temporal"}},
    {"sao",
     {"radius", "bias", "intensity", "samples", "spiral_turns", "blur_radius", "blur_step", "edge_sharpness", "csz32",
      "dual_layer", "temporal"}},
    {"cacao",
     {"radius", "quality", "shadow_multiplier", "shadow_power", "shadow_clamp", "horizon_angle_threshold", "fade_out_from",
      "fade_out_to", "adaptive_quality_limit", "blur_pass_count", "sharpness", "detail_shadow_strength", "generate_normals",
      "bilateral_sigma_squared", "bilateral_similarity_distance_sigma", "downsample"}},
    {"hemisphere_ssao", {"radius", "samples", "strength", "bias", "blur"}},  // examples/user_techniques/hemisphere_ssao
};

// The --technique value of a technique in kExpectedKeys: a built-in's name, an example's file.
std::string techniqueArgument(const std::string& name) {
  for (const auto& file : exampleTechniqueFiles())
    if (findTechnique(file).name == name) return file;
  return name;
}

// `techniques --json` lists the built-ins, and user techniques named with --technique.
std::string exampleOptions() {
  std::string options;
  for (const auto& file : exampleTechniqueFiles()) options += " --technique " + file;
  return options;
}

TEST(TechniqueKeys, TechniquesJsonListsEveryKeyWithItsDefaultAndRange) {
  auto r = runAoreplay("techniques --json" + exampleOptions());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  json list = json::parse(r.output)["techniques"];
  std::set<std::string> listed;
  for (const auto& t : list) {
    listed.insert(t["name"].get<std::string>());
    auto expected = kExpectedKeys.find(t["name"].get<std::string>());
    if (expected == kExpectedKeys.end()) continue;
    std::vector<std::string> keys;
    for (const auto& p : t["parameters"]) {
      keys.push_back(p["key"]);
      EXPECT_TRUE(p.contains("default") && p.contains("doc")) << p.dump();
      if (p["type"] != "enum") {
        EXPECT_TRUE(p.contains("min") && p.contains("max")) << p.dump();
      }
    }
    EXPECT_EQ(keys, expected->second) << t["name"];
  }
  for (const auto& [name, keys] : kExpectedKeys) EXPECT_TRUE(listed.count(name)) << name;
  // gtao's documented defaults and ranges (docs/guide.md): slices 3 in [1, 32], falloff 0.615, temporal 0.9 in [0, 0.98].
  for (const auto& t : list)
    if (t["name"] == "gtao")
      for (const auto& p : t["parameters"]) {
        if (p["key"] == "slices") {
          EXPECT_EQ(p["default"], 3);
          EXPECT_EQ(p["min"], 1);
          EXPECT_EQ(p["max"], 32);
        }
        if (p["key"] == "falloff") {
          EXPECT_EQ(p["default"], 0.615);
        }
        if (p["key"] == "temporal") {
          EXPECT_EQ(p["default"], 0.9);
          EXPECT_EQ(p["max"], 0.98);
        }
      }
}

TEST(TechniqueKeys, RunHelpListsTheKeysOfTheTechniqueNamed) {
  for (const auto& [name, keys] : kExpectedKeys) {
    auto r = runAoreplay(name == "gtao" ? "run --help" : fmt::format("run --technique {} --help", techniqueArgument(name)));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find(fmt::format("Keys of technique {}", name)), std::string::npos) << r.output;
    for (const auto& key : keys) EXPECT_NE(r.output.find("\n  " + key + " "), std::string::npos) << name << ": " << key;
  }
  // Keys of another technique are not offered: the reference has no slices.
  auto r = runAoreplay("run --technique reference --help");
  EXPECT_EQ(r.output.find("\n  slices "), std::string::npos) << r.output;
}

TEST(TechniqueKeys, ReportSettingsAndSweepColumnsHoldEveryKey) {
  auto capture = generatedCapture("boxes", "orbit", 32, 18, 2);
  for (const auto& [name, keys] : kExpectedKeys) {
    fs::path out = scratchDir("keys-" + name) / "out";
    auto r = runAoreplay(fmt::format("run {} --technique {} --no-images --out {}", capture.string(), techniqueArgument(name),
                                     out.string()));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    json settings = json::parse(std::ifstream(out / "report.json"))["settings"];
    for (const auto& key : keys) EXPECT_TRUE(settings.contains(key)) << name << " report.json lacks " << key;
    EXPECT_EQ(settings.size(), keys.size() + 1) << settings.dump() << " (the keys and `technique`)";
  }
  fs::path sweep = scratchDir("keys-sweep") / "out";
  std::string techniques;
  for (const auto& [name, keys] : kExpectedKeys) techniques += (techniques.empty() ? "" : ",") + techniqueArgument(name);
  auto r = runAoreplay(fmt::format("sweep {} --presets low --grid technique={} --repeat 1 --warmup 0 --out {}",
                                   capture.string(), techniques, sweep.string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::string csv = readText(sweep / "sweep.csv");
  std::string header = csv.substr(0, csv.find('\n'));
  for (const auto& [name, keys] : kExpectedKeys)
    for (const auto& key : keys) EXPECT_NE(("," + header + ",").find("," + key + ","), std::string::npos) << key << ": " << header;
}

TEST(TechniqueKeys, AKeyTheTechniqueLacksIsAnErrorListingItsKeys) {
  auto capture = generatedCapture("boxes", "orbit", 32, 18, 2);
  fs::path out = scratchDir("keys-unknown") / "out";
  auto r = runAoreplay(fmt::format("run {} --technique reference --set slices=4 --out {}", capture.string(), out.string()));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("technique reference has no setting 'slices'; its keys: radius, falloff, power, thin, bent"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(out));
  r = runAoreplay(fmt::format("run {} --technique nosuch --out {}", capture.string(), out.string()));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("unknown technique 'nosuch' (cacao, gtao, reference"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace aor::test
