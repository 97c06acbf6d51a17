// `aoreplay tune` end to end on shipped captures (few frames, few evaluations), its settings file
// read back by run and sweep, and its refusals.
#include <fstream>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "gpu_test_support.h"

namespace aor::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string shipped(const std::string& name) { return (fs::path(AOR_SOURCE_DIR) / "captures" / name).string(); }

std::string tuneArguments(const fs::path& out) {
  return fmt::format("tune {} {} --holdout {} --frames 0:2 --keys radius,power --max-evaluations 7 --out {}",
                     shipped("sphere-orbit"), shipped("bunny-orbit"), shipped("boxes-orbit"), out.string());
}

json readJson(const fs::path& file) { return json::parse(readText(file)); }

TEST(Tune, TwoTunesGiveTheSameTuneJsonAndTheBestIsNoWorseThanTheStart) {
  fs::path dir = scratchDir("tune-twice");
  auto a = runAoreplay(tuneArguments(dir / "a"));
  ASSERT_EQ(a.exitCode, 0) << a.output;
  auto b = runAoreplay(tuneArguments(dir / "b"));
  ASSERT_EQ(b.exitCode, 0) << b.output;
  EXPECT_EQ(readText(dir / "a" / "tune.json"), readText(dir / "b" / "tune.json"));

  json t = readJson(dir / "a" / "tune.json");
  ASSERT_EQ(t["evaluations"].size(), 7u);
  EXPECT_EQ(t["keys"][0]["key"], "radius_scale");
  EXPECT_EQ(t["keys"][1]["key"], "power");
  EXPECT_EQ(t["evaluations"][0]["phase"], "start");
  EXPECT_EQ(t["evaluations"][0]["values"]["radius_scale"], 1.0);
  double before = t["results"]["training"]["before"]["objective"], after = t["results"]["training"]["after"]["objective"];
  EXPECT_LE(after, before);
  EXPECT_EQ(after, t["best"]["objective"].get<double>());
  // The hold-out capture is scored before and after, and never searched on.
  ASSERT_EQ(t["results"]["holdout"]["before"]["captures"].size(), 1u);
  EXPECT_EQ(t["results"]["holdout"]["after"]["captures"][0]["capture"], "boxes-orbit");
  EXPECT_EQ(t["training"], (json{"sphere-orbit", "bunny-orbit"}));
  for (const char* file : {"tune_times.json", "tuned.settings.json", "tune_objective.svg", "tune_error_ms.svg"})
    EXPECT_TRUE(fs::is_regular_file(dir / "a" / file)) << file;
  EXPECT_NE(a.output.find("[7/7]"), std::string::npos) << "progress per evaluation: " << a.output;
}

// The FLIP objective is what is minimised and reported.
TEST(Tune, TheFlipObjectiveIsMeanLdrFlip) {
  fs::path dir = scratchDir("tune-flip");
  auto r = runAoreplay(fmt::format("tune {} --frames 0:1 --keys power --objective flip --max-evaluations 3 --out {}",
                                   shipped("bunny-orbit"), (dir / "out").string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  json t = readJson(dir / "out" / "tune.json");
  EXPECT_EQ(t["objective"], "flip");
  json before = t["results"]["training"]["before"]["captures"][0];
  EXPECT_EQ(before["objective"], before["flip"]);
  EXPECT_GT(before["flip"].get<double>(), 0.01);
  EXPECT_LT(before["flip"].get<double>(), 0.5);
  EXPECT_NE(before["flip"], before["rmse"]);
}

TEST(Tune, RunAndSweepTakeTheTunedSettingsFile) {
  fs::path dir = scratchDir("tune-settings");
  std::ofstream(dir / "s.json") << R"({"format": "aoreplay-settings", "version": 1, "technique": "gtao",
    "preset": "medium", "set": {"power": 2.25}, "radius_scale": 1.5})";
  auto run = runAoreplay(fmt::format("run {} --frames 0:1 --no-images --settings {} --out {}", shipped("pit-cut"),
                                     (dir / "s.json").string(), (dir / "run").string()));
  ASSERT_EQ(run.exitCode, 0) << run.output;
  json settings = readJson(dir / "run" / "report.json")["settings"];
  EXPECT_EQ(settings["power"], 2.25);
  EXPECT_EQ(settings["slices"], 2);                 // medium
  EXPECT_FLOAT_EQ(settings["radius"].get<float>(), 3.0f);  // pit-cut's ao_radius 2 x 1.5
  // --set on top of the file.
  auto over = runAoreplay(fmt::format("run {} --frames 0:1 --no-images --settings {} --set power=3 --out {}",
                                      shipped("pit-cut"), (dir / "s.json").string(), (dir / "run2").string()));
  ASSERT_EQ(over.exitCode, 0) << over.output;
  EXPECT_EQ(readJson(dir / "run2" / "report.json")["settings"]["power"], 3);
  auto sweep = runAoreplay(fmt::format("sweep {} --frames 0:1 --repeat 1 --settings {} --grid power=1,2 --out {}",
                                       shipped("pit-cut"), (dir / "s.json").string(), (dir / "sweep").string()));
  ASSERT_EQ(sweep.exitCode, 0) << sweep.output;
  json rows = readJson(dir / "sweep" / "sweep.json")["rows"];
  ASSERT_EQ(rows.size(), 2u);  // the file's preset only, times the grid
  EXPECT_FLOAT_EQ(rows[0]["settings"]["radius"].get<float>(), 3.0f);
}

TEST(Tune, BadSettingsFilesExit2NamingTheField) {
  fs::path dir = scratchDir("tune-bad-settings");
  struct Case {
    const char* text;
    const char* expected;
  } cases[] = {
      {R"({"format": "aoreplay-settings", "version": 1, "technique": "gtao", "sett": {}})", "sett"},
      {R"({"format": "aoreplay-settings", "version": 1, "technique": "gtao", "set": {"radius": 2}})", "set.radius"},
      {R"({"format": "aoreplay-settings", "version": 1, "technique": "gtao", "set": {"power": 99}})", "power"},
      {R"({"format": "aoreplay-settings", "version": 2, "technique": "gtao"})", "version"},
      {R"({"format": "aoreplay-settings", "version": 1, "technique": "nosuch"})", "nosuch"},
  };
  for (const auto& c : cases) {
    std::ofstream(dir / "bad.json") << c.text;
    auto r = runAoreplay(fmt::format("run {} --frames 0:1 --settings {} --out {}", shipped("pit-cut"),
                                     (dir / "bad.json").string(), (dir / "out").string()));
    EXPECT_EQ(r.exitCode, 2) << c.text << r.output;
    EXPECT_NE(r.output.find("bad.json"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(c.expected), std::string::npos) << c.expected << ": " << r.output;
    EXPECT_FALSE(fs::exists(dir / "out"));
  }
  std::ofstream(dir / "gtao.json") << R"({"format": "aoreplay-settings", "version": 1, "technique": "gtao"})";
  auto other = runAoreplay(fmt::format("run {} --technique reference --settings {} --out {}", shipped("pit-cut"),
                                       (dir / "gtao.json").string(), (dir / "out").string()));
  EXPECT_EQ(other.exitCode, 2) << other.output;
  EXPECT_NE(other.output.find("technique"), std::string::npos) << other.output;
}

TEST(Tune, ACaptureWithoutReferencesExits2NamingIt) {
  fs::path noRefs = generatedCapture("boxes", "orbit", 32, 18, 2);
  fs::path dir = scratchDir("tune-no-refs");
  auto r = runAoreplay(fmt::format("tune {} {} --max-evaluations 2 --out {}", shipped("pit-cut"), noRefs.string(),
                                   (dir / "out").string()));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find(noRefs.filename().string()), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("reference"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST(Tune, UnknownAndUntunableKeysExit2) {
  fs::path dir = scratchDir("tune-bad-keys");
  for (auto [keys, expected] : {std::pair{"nosuch", "no key 'nosuch'"}, std::pair{"power,slices", "'slices' of gtao is not tunable"}}) {
    auto r = runAoreplay(fmt::format("tune {} --keys {} --out {}", shipped("pit-cut"), keys, (dir / "out").string()));
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find(expected), std::string::npos) << r.output;
  }
  auto fixedAndTuned = runAoreplay(fmt::format("tune {} --keys power --set power=2 --out {}", shipped("pit-cut"), (dir / "out").string()));
  EXPECT_EQ(fixedAndTuned.exitCode, 2) << fixedAndTuned.output;
  auto objective = runAoreplay(fmt::format("tune {} --objective flop --out {}", shipped("pit-cut"), (dir / "out").string()));
  EXPECT_EQ(objective.exitCode, 2) << objective.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
}


// Captures with references, made here: two scenes far apart (a box city, a lone sphere).
fs::path libraryCapture(const fs::path& dir, const std::string& scene, const std::string& path) {
  fs::path out = dir / (scene + "-" + path);
  auto r = runAoreplay(fmt::format("capture {} --path {} --size 96x54 --frames 2 --reference-spp 32 --out {}", scene, path,
                                   out.string()));
  EXPECT_EQ(r.exitCode, 0) << r.output;
  return out;
}

// Issue 54: a fit that improves its training capture but worsens the one held out is refused, the
// fold named, and the defaults are what tuned.settings.json recommends.
TEST(TuneCrossValidation, AFitThatWorsensAHeldOutFoldIsRefusedWithTheFoldNamed) {
  fs::path dir = scratchDir("tune-cv-refused");
  fs::path boxes = libraryCapture(dir, "boxes", "orbit"), sphere = libraryCapture(dir, "sphere", "orbit");
  fs::path out = dir / "out";
  auto r = runAoreplay(fmt::format("tune {} {} --technique xegtao --cv --max-evaluations 12 --out {}", boxes.string(),
                                   sphere.string(), out.string()));
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("cross-validation: refused: fold 1 (held out boxes-orbit)"), std::string::npos) << r.output;
  auto tune = json::parse(readText(out / "tune.json"));
  const auto& cv = tune["cross_validation"];
  EXPECT_FALSE(cv["accepted"].get<bool>());
  EXPECT_EQ(cv["recommended"], "defaults");
  EXPECT_EQ(cv["refused_by"], "boxes-orbit");
  const auto& fold = cv["folds"][0];
  EXPECT_LT(fold["training_after"].get<double>(), fold["training_before"].get<double>()) << "the fit improved its training";
  EXPECT_GT(fold["after"].get<double>(), fold["before"].get<double>() * (1.0 + cv["margin"].get<double>()));
  // The recommended file is the untuned start: xegtao's defaults.
  auto recommended = json::parse(readText(out / "tuned.settings.json"));
  EXPECT_NE(recommended, tune["settings"]) << "the refused fit is not what is recommended";
  auto run = runAoreplay(fmt::format("run {} --frames 0:1 --no-images --settings {} --out {}", boxes.string(),
                                     (out / "tuned.settings.json").string(), (dir / "run").string()));
  ASSERT_EQ(run.exitCode, 0) << run.output;
  auto defaults = runAoreplay(fmt::format("run {} --technique xegtao --frames 0:1 --no-images --out {}", boxes.string(),
                                          (dir / "defaults").string()));
  ASSERT_EQ(defaults.exitCode, 0) << defaults.output;
  auto rmse = [](const fs::path& folder) {
    return json::parse(readText(folder / "report.json"))["metrics"]["error"]["rmse"].get<double>();
  };
  EXPECT_EQ(rmse(dir / "run"), rmse(dir / "defaults"));
}

// With a margin that no fold exceeds the fit on every capture is recommended, exit 0; a library
// folder stands for its captures (for sweep too); one capture is not enough to cross-validate; a
// folder holding no capture is exit 2.
TEST(TuneCrossValidation, AFitWithinTheMarginIsRecommendedAndALibraryFolderIsItsCaptures) {
  fs::path dir = scratchDir("tune-cv-accepted");
  fs::path library = dir / "library";
  libraryCapture(library, "boxes", "orbit");
  libraryCapture(library, "boxes", "strafe");
  fs::path out = dir / "out";
  auto r = runAoreplay(fmt::format("tune {} --keys power --cv --cv-margin 10 --max-evaluations 5 --out {}", library.string(),
                                   out.string()));
  EXPECT_EQ(r.exitCode, 0) << r.output;
  auto tune = json::parse(readText(out / "tune.json"));
  EXPECT_EQ(tune["training"], json::array({"boxes-orbit", "boxes-strafe"}));
  EXPECT_TRUE(tune["cross_validation"]["accepted"].get<bool>());
  EXPECT_EQ(tune["cross_validation"]["folds"].size(), 2u);
  EXPECT_EQ(json::parse(readText(out / "tuned.settings.json")), tune["settings"]);
  auto one = runAoreplay(fmt::format("tune {} --cv --out {}", (library / "boxes-orbit").string(), (dir / "one").string()));
  EXPECT_EQ(one.exitCode, 2) << one.output;
  EXPECT_NE(one.output.find("--cv"), std::string::npos) << one.output;
  // sweep takes the library too: each capture swept into OUT/<capture>/.
  auto sweep = runAoreplay(fmt::format("sweep {} --presets low --repeat 1 --out {}", library.string(), (dir / "sweep").string()));
  EXPECT_EQ(sweep.exitCode, 0) << sweep.output;
  for (const char* capture : {"boxes-orbit", "boxes-strafe"})
    EXPECT_EQ(json::parse(readText(dir / "sweep" / capture / "sweep.json"))["capture"], capture);
  auto empty = runAoreplay(fmt::format("tune {} --out {}", dir.string() + "/out", (dir / "none").string()));
  EXPECT_EQ(empty.exitCode, 2) << empty.output;
}

}  // namespace
}  // namespace aor::test
