// Issue 5, point 4 at the command line: every kind of bad capture makes `aoreplay run` exit with
// code 2 and print one message naming the file, the frame (when the problem has one) and the
// field or channel, and leaves nothing under --out (no result, no staging folder). Each case
// starts from a valid two-frame capture and breaks one thing; the control case shows the
// unbroken capture replays, so every failure comes from the break.
#include <algorithm>
#include <fstream>
#include <functional>
#include <iterator>
#include <sstream>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "capture/image_io.h"
#include "gpu_test_support.h"

namespace aor::test {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

constexpr int kW = 8, kH = 6;

void writeText(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary | std::ios::trunc) << text; }

// A valid 8x6 capture: two frames with depth and half normals, camera looking at a tilted plane.
fs::path validCapture(const fs::path& dir) {
  std::vector<CaptureFrameData> frames(2);
  for (int k = 0; k < 2; ++k) {
    auto& f = frames[size_t(k)];
    f.view = glm::lookAtRH(glm::vec3(0, 1, 2 + 0.1f * k), glm::vec3(0, 0, 0), glm::vec3(0, 1, 0));
    f.projection = glm::perspectiveRH_ZO(glm::radians(60.0f), float(kW) / kH, 0.1f, 100.0f);
    f.gbuffer.width = kW;
    f.gbuffer.height = kH;
    for (int i = 0; i < kW * kH; ++i) {
      f.gbuffer.depth.push_back(0.95f + 0.001f * float(i % kW));
      f.gbuffer.normals.insert(f.gbuffer.normals.end(), {0.0f, 1.0f, 0.0f});
    }
  }
  writeCapture(dir, kW, kH, frames, {{"ao_radius", 0.5}});
  return dir;
}

void writeDepthExr(const fs::path& path, int w, int h, ExrPixelType depthType, bool withDepth = true) {
  std::vector<float> depth(size_t(w) * size_t(h), 0.9f), zero(depth.size(), 0.0f), one(depth.size(), 1.0f);
  std::vector<ExrChannel> channels;
  if (withDepth) channels.push_back({"depth", depthType, depth.data()});
  channels.push_back({"normal.X", ExrPixelType::Half, zero.data()});
  channels.push_back({"normal.Y", ExrPixelType::Half, one.data()});
  channels.push_back({"normal.Z", ExrPixelType::Half, zero.data()});
  writeExr(path, w, h, channels);
}

struct BadCase {
  std::string name;
  std::function<void(const fs::path& capture)> breakIt;
  std::string file;   // as the message must spell it (a suffix of the path)
  int frame;          // -1: the problem belongs to no frame
  std::string field;  // JSON field or EXR channel, quoted in the message; empty: the file itself
  std::string problem;
};

json readDoc(const fs::path& c) { return json::parse(readText(c / "capture.json")); }
void editDoc(const fs::path& c, const std::function<void(json&)>& edit) {
  json doc = readDoc(c);
  edit(doc);
  writeText(c / "capture.json", doc.dump(2));
}

std::vector<BadCase> badCases() {
  std::vector<BadCase> cases;
  auto add = [&](BadCase c) { cases.push_back(std::move(c)); };
  add({"malformed_json", [](const fs::path& c) { writeText(c / "capture.json", "{\"format\": \"aoreplay-capture\",\n \"version\": 1,,}"); },
       "capture.json", -1, "", "parse error at line 2"});
  add({"wrong_format", [](const fs::path& c) { editDoc(c, [](json& d) { d["format"] = "aoreplay-trace"; }); },
       "capture.json", -1, "format", "expected \"aoreplay-capture\""});
  add({"wrong_version", [](const fs::path& c) { editDoc(c, [](json& d) { d["version"] = 2; }); },
       "capture.json", -1, "version", "version 2 is not supported"});
  add({"missing_field", [](const fs::path& c) { editDoc(c, [](json& d) { d["frames"][1].erase("projection"); }); },
       "capture.json", 1, "projection", "missing"});
  add({"extra_field", [](const fs::path& c) { editDoc(c, [](json& d) { d["frames"][1]["refrence"] = "x.exr"; }); },
       "capture.json", 1, "refrence", "unknown field (did you mean \"reference\"?)"});
  add({"extra_top_level_field_of_wrong_type",
       [](const fs::path& c) { editDoc(c, [](json& d) { d["widht"] = "8"; }); }, "capture.json", -1, "widht",
       "unknown field"});
  add({"width_wrong_type", [](const fs::path& c) { editDoc(c, [](json& d) { d["width"] = "8"; }); },
       "capture.json", -1, "width", "expected a positive integer, got string \"8\""});
  add({"cut_wrong_type", [](const fs::path& c) { editDoc(c, [](json& d) { d["frames"][1]["cut"] = 1; }); },
       "capture.json", 1, "cut", "expected true or false"});
  add({"singular_view",
       [](const fs::path& c) {
         editDoc(c, [](json& d) { d["frames"][1]["view"] = json::array({1, 0, 0, 0, 2, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}); });
       },
       "capture.json", 1, "view", "singular"});
  add({"singular_projection",
       [](const fs::path& c) { editDoc(c, [](json& d) { d["frames"][0]["projection"][0] = 0; }); }, "capture.json", 0,
       "projection", "singular"});
  add({"matrix_not_16_numbers",
       [](const fs::path& c) { editDoc(c, [](json& d) { d["frames"][0]["view"].erase(15); }); }, "capture.json", 0,
       "view", "expected 16 numbers, got 15"});
  add({"matrix_element_not_a_number",
       [](const fs::path& c) { editDoc(c, [](json& d) { d["frames"][1]["projection"][5] = "x"; }); }, "capture.json",
       1, "projection", "element 5 is not a number"});
  add({"missing_exr", [](const fs::path& c) { fs::remove(c / "frames/0001.exr"); }, "capture.json", 1, "gbuffer",
       "file \"frames/0001.exr\" does not exist"});
  add({"truncated_exr",
       [](const fs::path& c) { fs::resize_file(c / "frames/0001.exr", fs::file_size(c / "frames/0001.exr") / 2); },
       "frames/0001.exr", 1, "", "truncated"});
  add({"corrupt_exr", [](const fs::path& c) { writeText(c / "frames/0000.exr", std::string(300, '\x5a')); },
       "frames/0000.exr", 0, "", "not a readable OpenEXR file"});
  add({"missing_channel",
       [](const fs::path& c) { writeDepthExr(c / "frames/0001.exr", kW, kH, ExrPixelType::Float, false); },
       "frames/0001.exr", 1, "depth", "missing; a G-buffer needs a FLOAT channel named depth"});
  add({"wrong_channel_type", [](const fs::path& c) { writeDepthExr(c / "frames/0000.exr", kW, kH, ExrPixelType::Half); },
       "frames/0000.exr", 0, "depth", "has type HALF, expected FLOAT"});
  add({"size_mismatch_between_frames",
       [](const fs::path& c) { writeDepthExr(c / "frames/0001.exr", kW, kH - 1, ExrPixelType::Float); },
       "frames/0001.exr", 1, "", "image is 8x5 but capture.json says 8x6"});
  add({"dimensions_beyond_memory",
       [](const fs::path& c) { editDoc(c, [](json& d) { d["width"] = 16384; d["height"] = 16384; }); },
       "capture.json", -1, "height", "exceeds the limit of 67108864 pixels"});
  add({"width_beyond_limit", [](const fs::path& c) { editDoc(c, [](json& d) { d["width"] = 4000000000LL; }); },
       "capture.json", -1, "width", "exceeds the limit of 16384 pixels per side"});
  add({"path_leaves_the_capture_folder",
       [](const fs::path& c) { editDoc(c, [](json& d) { d["frames"][1]["gbuffer"] = "frames/../../outside.exr"; }); },
       "capture.json", 1, "gbuffer", "leaves the capture folder"});
  add({"symlink_leaves_the_capture_folder",
       [](const fs::path& c) {
         fs::copy_file(c / "frames/0001.exr", c.parent_path() / "outside.exr");
         fs::remove(c / "frames/0001.exr");
         fs::create_symlink(c.parent_path() / "outside.exr", c / "frames/0001.exr");
       },
       "capture.json", 1, "gbuffer", "outside the capture folder"});
  // Passes every check of loadCapture (structure intact) and fails only when frame 1's pixels are
  // decoded, after frame 0 was replayed and its images staged: the staging must not survive.
  add({"corrupt_pixel_data_found_mid_replay",
       [](const fs::path& c) {
         fs::path exr = c / "frames/0001.exr";
         writeDepthExr(exr, kW, kH, ExrPixelType::Float);  // constant channels: the chunk is compressed
         std::string bytes = readText(exr);
         std::fill(bytes.end() - 24, bytes.end(), '\x5a');
         writeText(exr, bytes);
       },
       "frames/0001.exr", 1, "", "cannot read pixel data"});
  return cases;
}

struct Workspace {
  fs::path capture, out;
};

Workspace workspace(const std::string& name) {
  fs::path dir = scratchDir("bad-input-cli-" + name);
  fs::create_directories(dir / "out");
  return {validCapture(dir / "capture"), dir / "out" / "result"};
}

std::vector<std::string> nonEmptyLines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) lines.push_back(line);
  return lines;
}

TEST(BadInputCli, ControlTheUnbrokenCaptureReplays) {
  Workspace w = workspace("control");
  auto run = runAoreplay(fmt::format("run '{}' --out '{}'", w.capture.string(), w.out.string()));
  EXPECT_EQ(run.exitCode, 0) << run.output;
  EXPECT_TRUE(fs::exists(w.out / "report.json"));
  EXPECT_TRUE(fs::exists(w.out / "ao/0001.exr"));
}

class BadInputCli : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadInputCli, ExitCode2OneMessageNamingFileFrameFieldAndNothingUnderOut) {
  const BadCase& c = GetParam();
  Workspace w = workspace(c.name);
  c.breakIt(w.capture);
  auto run = runAoreplay(fmt::format("run '{}' --out '{}'", w.capture.string(), w.out.string()));
  EXPECT_EQ(run.exitCode, 2) << run.output;
  auto lines = nonEmptyLines(run.output);
  ASSERT_EQ(lines.size(), 1u) << run.output;
  const std::string& message = lines[0];
  EXPECT_EQ(message.rfind("aoreplay: error: ", 0), 0u) << message;
  // The file: its path inside the capture folder, after the folder (spelt as given, or relative to
  // the working directory for files opened during the replay).
  EXPECT_NE(message.find("/capture/" + c.file + ": "), std::string::npos) << message;
  if (c.frame >= 0) {
    EXPECT_NE(message.find(fmt::format(": frame {}: ", c.frame)), std::string::npos) << message;
  } else {
    EXPECT_EQ(message.find(": frame "), std::string::npos) << message;
  }
  if (!c.field.empty()) {
    EXPECT_NE(message.find(fmt::format("\"{}\": ", c.field)), std::string::npos) << message;
  }
  EXPECT_NE(message.find(c.problem), std::string::npos) << message;
  // Nothing under --out: not the result, not a staging folder beside it.
  EXPECT_FALSE(fs::exists(w.out)) << w.out;
  EXPECT_TRUE(fs::is_empty(w.out.parent_path())) << "left behind in " << w.out.parent_path();
}

INSTANTIATE_TEST_SUITE_P(Corpus, BadInputCli, ::testing::ValuesIn(badCases()),
                         [](const ::testing::TestParamInfo<BadCase>& info) { return info.param.name; });

}  // namespace
}  // namespace aor::test

namespace aor::test {
namespace {

// A one-frame run of boxes-orbit under `dir`: its report.json.
std::string oneFrameReport(const fs::path& dir) {
  const std::string capture = (fs::path(AOR_SOURCE_DIR) / "captures" / "boxes-orbit").string();
  EXPECT_EQ(runAoreplay(fmt::format("run {} --frames 0:1 --no-images --out {}", capture, (dir / "run").string())).exitCode, 0);
  return (dir / "run" / "report.json").string();
}

// Every numeric option goes through one check (cli/number_options.h): NaN, infinities and numbers
// past a double are refused with exit 2 and the option's range, before any work. Before it,
// `compare --alpha nan` turned a x1e308 slowdown into exit 0.
TEST(BadInputCli, NonFiniteNumbersAreRefusedByEveryNumericOption) {
  const std::string capture = (std::filesystem::path(AOR_SOURCE_DIR) / "captures" / "boxes-orbit").string();
  const std::vector<std::pair<std::string, std::string>> options = {
      {"compare a.json b.json", "--alpha"},        {"compare a.json b.json", "--min-effect"},
      {"compare a.json b.json", "--min-effect-ms"}, {"compare a.json b.json", "--spread-multiple"},
      {"ab " + capture + " --rounds 1", "--alpha"}, {"trend", "--alpha"},
      {"trend", "--min-effect"},                    {"run " + capture, "--jump-angle"},
      {"run " + capture, "--jump-distance"},        {"run " + capture, "--preload-budget"},
      {"tune " + capture, "--budget-ms"},           {"capture boxes --out x", "--fov"}};
  for (const auto& [command, option] : options)
    for (const char* value : {"nan", "-nan", "inf", "-inf", "1e999"}) {
      const auto r = runAoreplay(fmt::format("{} {} {}", command, option, value));
      EXPECT_EQ(r.exitCode, 2) << command << " " << option << " " << value << "\n" << r.output;
      EXPECT_NE(r.output.find(fmt::format("{}: '{}' is not a finite number in [", option, value)), std::string::npos)
          << r.output;
    }
  const auto zero = runAoreplay("tune " + capture + " --budget-ms 0");
  EXPECT_EQ(zero.exitCode, 2) << "a budget of 0 ms was silently ignored";
  const auto whole = runAoreplay("run " + capture + " --repeat 2.5");
  EXPECT_EQ(whole.exitCode, 2);
  EXPECT_NE(whole.output.find("--repeat: '2.5' is not a whole number in [1, 100000]"), std::string::npos) << whole.output;
}

// Standard output is checked once for every command (cli/main.cpp): a verdict that could not be
// written (a full disk here) is exit 1, never a silent 0.
TEST(BadInputCli, AnUnwritableStandardOutputIsAFailure) {
  const fs::path dir = scratchDir("stdout-full");
  const std::string report = oneFrameReport(dir);
  EXPECT_EQ(runAoreplay(fmt::format("compare {} {} --json - > {}", report, report, (dir / "ok.json").string())).exitCode, 0);
  EXPECT_EQ(runAoreplay(fmt::format("compare {} {} --json - >/dev/full", report, report)).exitCode, 1);
  EXPECT_EQ(runAoreplay(fmt::format("compare {} {} >/dev/full", report, report)).exitCode, 1);
  EXPECT_EQ(runAoreplay("devices >/dev/full").exitCode, 1);
}

// Values given twice or empty, which used to pass (the later one won, or nothing was stored):
// each is exit 2 naming the option, before any work.
TEST(BadInputCli, RepeatedKeysAndEmptyValuesAreRefused) {
  const fs::path dir = scratchDir("repeated-values");
  const std::string capture = (fs::path(AOR_SOURCE_DIR) / "captures" / "boxes-orbit").string();
  const std::string report = oneFrameReport(dir);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"sweep " + capture + " --grid slices=1,2 --grid slices=3", "--grid\": 'slices=3' is a second axis of key 'slices'"},
      {"sweep " + capture + " --grid technique=gtao --grid technique=sao", "is a second axis of key 'technique'"},
      {"tune " + capture + " --keys power,power", "--keys\": key 'power' is named twice"},
      {"tune " + capture + " --range power=1:2:3", "--range\": 'power=1:2:3' is not KEY=MIN:MAX"},
      {"tune " + capture + " --range power=1:2 --range power=1:3", "--range\": key 'power' is given twice"},
      {"record " + report + " --db sqlite: --commit abc --ordinal 1", "--db\": names no file"},
      {"record " + report + " --db " + (dir / "s.db").string() + " --commit '' --ordinal 1", "--commit: is empty"}};
  for (const auto& [arguments, says] : cases) {
    const auto r = runAoreplay(arguments);
    EXPECT_EQ(r.exitCode, 2) << arguments << "\n" << r.output;
    EXPECT_NE(r.output.find(says), std::string::npos) << arguments << "\n" << r.output;
  }
  EXPECT_FALSE(fs::exists(dir / "s.db")) << "nothing stored for an empty commit";
}

// `record` once added its tables to any SQLite file it was given; one that has tables of its own
// and no aoreplay schema version is refused, and left as it was.
TEST(BadInputCli, AnotherProgramsSqliteFileIsNotTakenAsAStore) {
  const fs::path dir = scratchDir("foreign-sqlite");
  const std::string report = oneFrameReport(dir);
  const fs::path db = dir / "notes.db";
  ASSERT_EQ(std::system(fmt::format("sqlite3 {} \"CREATE TABLE notes (x TEXT)\"", db.string()).c_str()), 0);
  const auto r = runAoreplay(fmt::format("record {} --db {} --commit abc --ordinal 1", report, db.string()));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("is an SQLite database of something else"), std::string::npos) << r.output;
  const fs::path tables = dir / "tables.txt";
  ASSERT_EQ(std::system(fmt::format("sqlite3 {} .tables > {}", db.string(), tables.string()).c_str()), 0);
  EXPECT_EQ(readText(tables), "notes\n") << "no table of the store was added";
}

// Issue 44, class 8: one rule for control characters (core/plain_text.h). Every command-line
// value, technique.json's strings and report.json's names refuse them where they come in, so a
// commit string cannot recolour the terminal and a parameter's doc cannot add a line to the
// generated GLSL; an empty value (`--out ''` once wrote into out/) is refused the same way.
TEST(BadInputCli, ControlCharactersAndEmptyValuesAreRefusedWhereTheyComeIn) {
  const fs::path dir = scratchDir("control-characters");
  const std::string capture = (fs::path(AOR_SOURCE_DIR) / "captures" / "boxes-orbit").string();
  const std::string report = oneFrameReport(dir);
  json named = json::parse(readText(report));
  named["passes"][0]["name"] = std::string("gtao\x01");
  writeText(dir / "named.json", named.dump());
  const fs::path technique = dir / "technique";
  fs::create_directories(technique);
  writeText(technique / "technique.json", R"({"format": "aoreplay-technique", "version": 1, "name": "doc",
    "parameters": {"k": {"type": "float", "default": 1, "min": 0, "max": 2, "doc": "a doc\n#define k 0.0"}},
    "passes": [{"name": "shade", "shader": "shade.comp", "writes": [{"name": "ao", "format": "r16f"}]}], "output": "ao"})");
  writeText(technique / "shade.comp", "#version 450\n#include \"aoreplay.glsl\"\nvoid main() {}\n");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"run " + capture + " --out ''", "--out: is empty"},
      {"run " + capture + " --out \"$(printf 'a\\nb')\"", "--out: a\\x0ab holds a control character (\\x0a at byte 1)"},
      {"record " + report + " --db " + (dir / "s.db").string() + " --commit \"$(printf 'abc\\033[31m')\" --ordinal 1", "--commit: abc\\x1b[31m holds a control character"},
      {"compare " + report + " " + (dir / "named.json").string(), "field \"passes[0].name\": \"gtao\\u0001\" holds a control character"},
      {"technique-header " + (technique / "technique.json").string() + " shade", "field \"parameters.k.doc\": \"a doc\\n#define k 0.0\" holds a control character"}};
  for (const auto& [arguments, says] : cases) {
    const auto r = runAoreplay(arguments);
    EXPECT_EQ(r.exitCode, 2) << arguments << "\n" << r.output;
    EXPECT_NE(r.output.find(says), std::string::npos) << arguments << "\n" << r.output;
    EXPECT_EQ(r.output.find('\x1b'), std::string::npos) << "no control character reaches the terminal: " << arguments;
  }
  EXPECT_FALSE(fs::exists(dir / "s.db"));
}

// Issue 44, class 7: a sweep's size is counted before any configuration is made; past
// --max-configurations (default 1000) it is refused at once. A 4 x 10^6 grid ran for hours before.
TEST(BadInputCli, ASweepGridPastMaxConfigurationsIsRefusedBeforeAnyWork) {
  const std::string capture = (fs::path(AOR_SOURCE_DIR) / "captures" / "boxes-orbit").string();
  const fs::path out = scratchDir("huge-grid") / "out";
  std::string grid;
  for (const char* key : {"slices", "steps", "radius", "power", "falloff", "thin"})
    grid += fmt::format(" --grid {}=1,2,3,4,5,6,7,8,9,10", key);
  auto r = runAoreplay(fmt::format("sweep {}{} --out {}", capture, grid, out.string()));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("\"--grid\": 4000000 configurations are more than --max-configurations (1000)"), std::string::npos) << r.output;
  r = runAoreplay(fmt::format("sweep {} --grid slices=1,2 --max-configurations 7 --out {}", capture, out.string()));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("8 configurations are more than --max-configurations (7)"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

// Issue 44, class 9: a commit's position is stored as seconds and printed by every export as an ISO
// date; one past 9999-12-31 (or an ordinal past int64, once clamped) is refused when recorded, and
// the last printable second is stored and exported.
TEST(BadInputCli, CommitPositionsEveryExportCannotPrintAreRefusedWhenRecorded) {
  const fs::path dir = scratchDir("positions");
  const std::string report = oneFrameReport(dir);
  const std::string db = (dir / "s.db").string();
  for (const std::string position : {"--ordinal 253402300800", "--ordinal 99999999999999999999", "--ordinal -1",
                                      "--date @253402300800", "--date @-99999999999999999999", "--date 0000-12-31"}) {
    auto r = runAoreplay(fmt::format("record {} --db {} --commit abc {}", report, db, position));
    EXPECT_EQ(r.exitCode, 2) << position << "\n" << r.output;
    EXPECT_FALSE(fs::exists(db)) << position;
  }
  ASSERT_EQ(runAoreplay(fmt::format("record {} --db {} --commit abc --ordinal 253402300799", report, db)).exitCode, 0);
  for (const char* format : {"google-benchmark", "bencher", "otava"}) {
    auto r = runAoreplay(fmt::format("export --db {} --format {}", db, format));
    EXPECT_EQ(r.exitCode, 0) << format << "\n" << r.output;
  }
  EXPECT_NE(runAoreplay(fmt::format("export --db {} --format otava", db)).output.find("9999-12-31T23:59:59Z"), std::string::npos);
}

// Issue 44, class 9: a store damaged past its first page opens fine and fails at the first read;
// that is exit 2 with a plain message (it was exit 1 with the SQL statement that hit the damage).
TEST(BadInputCli, ADamagedStoreIsBadInputSaidPlainly) {
  const fs::path dir = scratchDir("damaged-store");
  const std::string report = oneFrameReport(dir);
  const fs::path db = dir / "s.db";
  ASSERT_EQ(runAoreplay(fmt::format("record {} --db {} --commit abc --ordinal 1", report, db.string())).exitCode, 0);
  std::string bytes = readText(db);
  ASSERT_GT(bytes.size(), 8192u);
  for (size_t i = 4096; i < bytes.size(); i += 3) bytes[i] = char(bytes[i] ^ 0xa5);  // every page but the schema's
  writeText(db, bytes);
  for (const std::string& command : {"trend --db " + db.string(), "export --format otava --db " + db.string(),
                                     fmt::format("record {} --db {} --commit def --ordinal 2", report, db.string())}) {
    const auto r = runAoreplay(command);
    EXPECT_EQ(r.exitCode, 2) << command << "\n" << r.output;
    EXPECT_NE(r.output.find("field \"--db\": the store is damaged (database disk image is malformed)"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("SELECT"), std::string::npos) << r.output;
  }
}

}  // namespace
}  // namespace aor::test
