// User techniques (user_techniques/FORMAT.md): the shipped example replayed with run and sweep like a
// built-in, bad technique files and shaders refused with exit 2 and nothing written, the generated
// header, the shader cache, history / seed000 / half-scale writes, and FORMAT.md's own example
// compiled and run so the document cannot drift from the tool.
#include <sys/stat.h>

#include <cstdlib>
#include <fstream>
#include <regex>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/input_error.h"
#include "gpu_test_support.h"
#include "techniques/user/shader_compiler.h"
#include "techniques/user/user_technique.h"
#include "techniques/user/user_technique_spec.h"

namespace aor::test {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

fs::path shipped(const std::string& name) { return fs::path(AOR_SOURCE_DIR) / "captures" / name; }
std::string example() { return (fs::path(AOR_SOURCE_DIR) / "examples/user_techniques/hemisphere_ssao/technique.json").string(); }

void writeFile(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

// A technique folder under the test's scratch: technique.json and its files.
fs::path writeTechnique(const std::string& name, const std::string& techniqueJson, const std::map<std::string, std::string>& files) {
  fs::path dir = scratchDir("technique-" + name);
  writeFile(dir / "technique.json", techniqueJson);
  for (const auto& [file, text] : files) writeFile(dir / file, text);
  return dir / "technique.json";
}

// One pass writing `ao` from linear depth: the smallest valid technique, for the error cases.
std::string onePassJson(const std::string& name, const std::string& extraRoot = "", const std::string& reads = R"(["linear_depth"])") {
  return fmt::format(R"({{"format": "aoreplay-technique", "version": 1, "name": "{}",{}
  "passes": [{{"name": "shade", "shader": "shade.comp", "reads": {}, "writes": [{{"name": "ao", "format": "r16f"}}]}}],
  "output": "ao"}})",
                     name, extraRoot, reads);
}
const char* kShadeShader = R"(#version 450
#include "aoreplay.glsl"
void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(vec2(pixel), frame.size))) return;
  imageStore(out_ao, pixel, vec4(texelFetch(in_linear_depth, pixel, 0).r > 0.0 ? 0.75 : 1.0));
}
)";

TEST(UserTechniqueExample, RunsValidatedTwiceBitIdenticalWithErrorAndTemporalMetrics) {
  auto runOnce = [&](const std::string& tag) {
    fs::path out = scratchDir("example-run-" + tag) / "out";
    auto r = runAoreplay(fmt::format("run {} --technique {} --frames 0:4 --validate --out {}", shipped("boxes-orbit").string(),
                                     example(), out.string()));
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("validation: 0 messages"), std::string::npos) << r.output;
    return out;
  };
  fs::path a = runOnce("a"), b = runOnce("b");
  int compared = 0;
  for (const auto& entry : fs::directory_iterator(a / "ao")) {
    if (entry.path().extension() != ".exr") continue;
    EXPECT_EQ(readText(entry.path()), readText(b / "ao" / entry.path().filename())) << entry.path();
    ++compared;
  }
  EXPECT_EQ(compared, 4);
  json report = json::parse(std::ifstream(a / "report.json"));
  EXPECT_EQ(report["settings"]["technique"], "hemisphere_ssao");
  EXPECT_EQ(report["settings"]["samples"], 16);  // the default preset, medium
  EXPECT_EQ(report["run"]["technique_file"], example());
  ASSERT_TRUE(report["metrics"].contains("error")) << report["metrics"].dump();
  EXPECT_GT(report["metrics"]["error"]["rmse"].get<double>(), 0.0);
  EXPECT_LT(report["metrics"]["error"]["rmse"].get<double>(), 0.3);
  ASSERT_TRUE(report["metrics"].contains("temporal")) << report["metrics"].dump();
  std::set<std::string> passes;
  for (const auto& p : report["passes"]) passes.insert(p["name"].get<std::string>());
  for (const char* pass : {"ssao", "blur", "constants", "linear_depth"}) EXPECT_TRUE(passes.count(pass)) << pass << " " << report["passes"].dump();
}

TEST(UserTechniqueExample, SweepPutsItBesideGtaoOnOnePlot) {
  fs::path out = scratchDir("example-sweep") / "out";
  auto r = runAoreplay(fmt::format("sweep {} --presets low --grid technique=gtao,{} --frames 0:2 --repeat 1 --warmup 0 --out {}",
                                   shipped("boxes-orbit").string(), example(), out.string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::string csv = readText(out / "sweep.csv");
  EXPECT_NE(csv.find("technique=gtao"), std::string::npos) << csv;
  EXPECT_NE(csv.find("technique=hemisphere_ssao"), std::string::npos) << csv;
  int plots = 0;
  for (const auto& entry : fs::directory_iterator(out)) {
    if (entry.path().extension() != ".svg") continue;
    std::string svg = readText(entry.path());
    if (svg.find("technique=gtao") != std::string::npos && svg.find("technique=hemisphere_ssao") != std::string::npos) ++plots;
  }
  EXPECT_GE(plots, 1) << "no plot shows both";
}

// An earlier result in --out, to show a refused technique leaves it as it was.
fs::path earlierResult(const std::string& name) {
  fs::path out = scratchDir("earlier-" + name) / "out";
  auto r = runAoreplay(fmt::format("run {} --frames 0:1 --no-images --out {}", shipped("boxes-static").string(), out.string()));
  EXPECT_EQ(r.exitCode, 0) << r.output;
  return out;
}

void expectRefused(const fs::path& technique, const std::vector<std::string>& mentions, const std::string& name) {
  fs::path out = earlierResult(name);
  std::string before = readText(out / "report.json");
  auto r = runAoreplay(fmt::format("run {} --technique {} --frames 0:1 --out {}", shipped("boxes-static").string(), technique.string(),
                                   out.string()));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  for (const auto& m : mentions) EXPECT_NE(r.output.find(m), std::string::npos) << "missing '" << m << "' in\n" << r.output;
  EXPECT_EQ(readText(out / "report.json"), before);
  EXPECT_FALSE(fs::exists(out / "ao"));
}

TEST(UserTechniqueErrors, AShaderSyntaxErrorExits2NamingTheFileAndLine) {
  std::string bad = kShadeShader;
  bad.replace(bad.find("if (any"), 0, "float x = ;\n  ");  // line 5
  auto file = writeTechnique("syntax", onePassJson("syntax_error"), {{"shade.comp", bad}});
  expectRefused(file, {"shade.comp:5:", "error", "passes[0].shader"}, "syntax");
}

// An #include that fans out (each level including the next twice, 24 levels: 2^24 expansions)
// ran past 125 s at 3.3 GB; a budget over the shader's whole expansion stops it at once.
TEST(UserTechniqueErrors, AnIncludeBombExits2) {
  std::map<std::string, std::string> files;
  std::string shader = kShadeShader;
  shader.insert(shader.find('\n', shader.find("aoreplay.glsl")) + 1, "#include \"level0.glsl\"\n");
  files["shade.comp"] = shader;
  for (int level = 0; level < 24; ++level)
    files[fmt::format("level{}.glsl", level)] =
        level + 1 < 24 ? fmt::format("#include \"level{0}.glsl\"\n#include \"level{0}.glsl\"\n", level + 1) : "// leaf\n";
  auto file = writeTechnique("include-bomb", onePassJson("include_bomb"), files);
  expectRefused(file, {"more than 1000 #include expansions in one shader", "passes[0].shader"}, "include-bomb");
}

TEST(UserTechniqueErrors, AReadOfAnUndeclaredNameExits2NamingIt) {
  auto file = writeTechnique("undeclared", onePassJson("undeclared", "", R"(["linear_depth", "ao_blurred"])"), {{"shade.comp", kShadeShader}});
  expectRefused(file, {"technique.json", "passes[0].reads[1]", "'ao_blurred'"}, "undeclared");
}

TEST(UserTechniqueErrors, AnUnknownKeyExits2NamingIt) {
  auto file = writeTechnique("unknown-key", onePassJson("unknown_key", R"( "colour": "red",)"), {{"shade.comp", kShadeShader}});
  expectRefused(file, {"technique.json", "\"colour\"", "unknown key"}, "unknown-key");
}

// The loader's checks, in process: each file is refused with the key it names.
TEST(UserTechniqueSpec, EveryRuleIsCheckedAndNamesTheKey) {
  struct Case {
    std::string json, field, words;
  };
  auto pass = [](const std::string& name, const std::string& reads, const std::string& writes) {
    return fmt::format(R"({{"name": "{}", "shader": "shade.comp", "reads": {}, "writes": {}}})", name, reads, writes);
  };
  auto doc = [](const std::string& passes, const std::string& extra = "", const std::string& output = "ao") {
    return fmt::format(R"({{"format": "aoreplay-technique", "version": 1, "name": "t",{} "passes": [{}], "output": "{}"}})", extra,
                       passes, output);
  };
  const std::string ao = R"([{"name": "ao", "format": "r16f"}])";
  const std::vector<Case> cases = {
      {R"({"format": "aoreplay-technique", "version": 2, "name": "t", "passes": [], "output": "ao"})", "version", "not supported"},
      {doc(pass("shade", "[]", ao), R"( "name": "T",)"), "", "appears twice"},  // a key twice: the bounded reader
      {doc(pass("Shade", "[]", ao)), "passes[0].name", "[a-z][a-z0-9_]*"},
      {doc(pass("spatial", "[]", ao)), "passes[0].name", "shared block"},
      {doc(pass("a", "[]", ao) + "," + pass("a", "[\"ao\"]", R"([{"name": "ao2", "format": "r16f"}])"), "", "ao2"), "passes[1].name",
       "duplicate pass name"},
      {doc(pass("a", "[\"ao\"]", ao)), "passes[0].reads[0]", "nor written by an earlier pass"},  // its own write
      {doc(pass("a", "[]", R"([{"name": "ao", "format": "r16"}])")), "passes[0].writes[0].format", "unknown format"},
      {doc(pass("a", "[]", R"([{"name": "ao", "format": "r16f", "scale": "quarter"}])")), "passes[0].writes[0].scale", "full or half"},
      {doc(pass("a", "[]", R"([{"name": "ao", "format": "r16f", "scale": "half"}])")), "output", "full scale"},
      {doc(pass("a", "[]", R"([{"name": "ao", "format": "r16f"}, {"name": "spare", "format": "r8"}])")),
       "passes[0].writes[1].name", "no pass reads it"},
      {doc(pass("a", "[]", R"([{"name": "depth", "format": "r32f"}])"), "", "depth"), "passes[0].writes[0].name", "built-in"},
      {doc(pass("a", "[]", R"([{"name": "ao", "format": "rgba8"}])"), R"( "denoise": "seed000",)"), "output", "must be r16f"},
      {doc(pass("a", "[]", ao), R"( "denoise": "temporal",)"), "denoise", "none or seed000"},
      {doc(pass("a", "[]", ao), R"( "parameters": {"radius": {"type": "float", "default": 1, "min": 0, "max": 2}},)"),
       "parameters.radius", "shared key"},
      {doc(pass("a", "[]", ao), R"( "parameters": {"sample": {"type": "int", "default": 1, "min": 0, "max": 2}},)"),
       "parameters.sample", "GLSL word"},
      {doc(pass("a", "[]", ao), R"( "parameters": {"n": {"type": "int", "default": 9, "min": 0, "max": 2}},)"), "parameters.n.default",
       "outside"},
      {doc(pass("a", "[]", ao), R"( "parameters": {"n": {"type": "int", "default": 1, "min": 0, "max": 2, "step": 1}},)"),
       "parameters.n.step", "unknown key"},
      {doc(pass("a", "[]", ao), R"( "parameters": {"n": {"type": "enum", "choices": ["x", "y"], "default": "z"}},)"),
       "parameters.n.default", "not one of the choices"},
      {doc(pass("a", "[]", ao), R"( "presets": {"low": {"m": 1}},)"), "presets.low.m", "unknown parameter"},
      {doc(pass("a", "[]", ao), R"( "default_preset": "high",)"), "default_preset", "not one of the presets"},
      {doc(R"({"name": "a", "shader": "../shade.comp", "writes": [{"name": "ao", "format": "r16f"}]})"), "passes[0].shader",
       "leaves the technique's folder"},
      {doc(R"({"name": "a", "shader": "/etc/passwd", "writes": [{"name": "ao", "format": "r16f"}]})"), "passes[0].shader", "absolute"},
      {doc(R"({"name": "a", "shader": "missing.comp", "writes": [{"name": "ao", "format": "r16f"}]})"), "passes[0].shader",
       "does not exist"},
      {doc(R"({"name": "a", "shader": "shade.comp", "writes": [{"name": "ao", "format": "r16f"}], "workgroup": [64, 32]})"),
       "passes[0].workgroup", "exceed 1024"},
  };
  fs::path dir = scratchDir("spec-cases");
  writeFile(dir / "shade.comp", kShadeShader);
  for (size_t i = 0; i < cases.size(); ++i) {
    fs::path file = dir / fmt::format("case{}.json", i);
    writeFile(file, cases[i].json);
    try {
      loadUserTechniqueSpec(file, "case.json");
      ADD_FAILURE() << "accepted case " << i << ": " << cases[i].json;
    } catch (const InputError& e) {
      EXPECT_EQ(e.file, "case.json") << i;
      if (!cases[i].field.empty()) {
        EXPECT_EQ(e.field, cases[i].field) << i << ": " << e.what();
      }
      EXPECT_NE(std::string(e.what()).find(cases[i].words), std::string::npos) << i << ": " << e.what();
    }
  }
}

TEST(UserTechniqueSpec, AShaderWithoutTheHeaderOrWithItsOwnBindingIsRefused) {
  std::string noInclude = "#version 450\nlayout(local_size_x = 8, local_size_y = 8) in;\nvoid main() {}\n";
  std::string ownBinding = kShadeShader;
  ownBinding.replace(ownBinding.find("void main"), 0, "layout(set = 0, binding = 3) uniform sampler2D extra;\n");
  ownBinding.replace(ownBinding.find("imageStore"), 0, "if (texelFetch(extra, pixel, 0).r > 2.0) return;\n  ");
  for (const auto& [shader, words] : std::vector<std::pair<std::string, std::string>>{
           {noInclude, "shade.comp:2: error: #include \"aoreplay.glsl\" must follow #version"},
           {ownBinding, "of its own; bindings come from aoreplay.glsl"}}) {
    auto file = writeTechnique("own-binding", onePassJson("own"), {{"shade.comp", shader}});
    auto r = runAoreplay(fmt::format("graph {} --technique {}", shipped("boxes-static").string(), file.string()));
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find(words), std::string::npos) << r.output;
  }
}

TEST(UserTechniqueHeader, DeclaresEveryBindingAndCompilesOfflineWithGlslc) {
  auto r = runAoreplay(fmt::format("technique-header {} ssao", example()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* line : {"layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;",
                           "layout(set = 0, binding = 0, std140) uniform AoreplayFrame {", "  mat4 prev_view_projection;",
                           "  float radius;", "} frame;", "layout(set = 0, binding = 1, std140) uniform AoreplayParams {",
                           "  int samples;", "  float strength;", "  float bias;", "  int blur;", "} params;",
                           "layout(set = 0, binding = 2) uniform sampler2D in_linear_depth;",
                           "layout(set = 0, binding = 3) uniform sampler2D in_view_normals;",
                           "layout(set = 0, binding = 4, r16f) uniform writeonly image2D out_ao_raw;"})
    EXPECT_NE(r.output.find(line), std::string::npos) << line << "\n" << r.output;
  // Offline, as FORMAT.md says: the header beside the example's shaders, through glslc.
  fs::path dir = scratchDir("offline");
  writeFile(dir / "aoreplay.glsl", r.output);
  fs::path source = fs::path(example()).parent_path();
  fs::copy_file(source / "ssao.comp", dir / "ssao.comp");
  fs::copy_file(source / "common.glsl", dir / "common.glsl");
  std::string command = fmt::format("glslc -fshader-stage=compute --target-env=vulkan1.2 -o {0}/ssao.spv {0}/ssao.comp > {0}/log 2>&1",
                                    dir.string());
  EXPECT_EQ(std::system(command.c_str()), 0) << readText(dir / "log");
  r = runAoreplay(fmt::format("technique-header {} nosuch", example()));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("no pass 'nosuch' (passes: ssao, blur)"), std::string::npos) << r.output;
}

TEST(UserTechniqueCache, ASecondCompileIsACacheHitAndAChangedIncludeIsCompiledAnew) {
  fs::path cache = scratchDir("cache");
  std::string previous = std::getenv("AOREPLAY_SHADER_CACHE") ? std::getenv("AOREPLAY_SHADER_CACHE") : "";
  ::setenv("AOREPLAY_SHADER_CACHE", cache.c_str(), 1);
  std::string shader = std::string("#version 450\n#include \"aoreplay.glsl\"\n#include \"lib/value.glsl\"\n") +
                       "void main() { imageStore(out_ao, ivec2(gl_GlobalInvocationID.xy), vec4(kValue)); }\n";
  auto file = writeTechnique("cache", onePassJson("cached", "", "[]"), {{"shade.comp", shader}, {"lib/value.glsl", "const float kValue = 0.5;\n"}});
  auto spec = loadUserTechniqueSpec(file, "technique.json");
  auto first = compileUserPass(spec, 0), second = compileUserPass(spec, 0);
  EXPECT_FALSE(first.fromCache);
  EXPECT_TRUE(second.fromCache);
  EXPECT_EQ(first.spirv, second.spirv);
  writeFile(file.parent_path() / "lib/value.glsl", "const float kValue = 0.25;\n");
  auto third = compileUserPass(spec, 0);
  EXPECT_FALSE(third.fromCache);
  EXPECT_NE(third.spirv, first.spirv);
  ::setenv("AOREPLAY_SHADER_CACHE", previous.c_str(), 1);
}

// Issue 44: a cache entry is input like any other. One that is a FIFO, a link to /dev/zero, torn,
// or another shader's valid SPIR-V under this key is not used: the shader is compiled anew (the
// same SPIR-V as a cold compile), the entry replaced, and nothing is blamed on the user's shader.
TEST(UserTechniqueCache, ABadEntryIsCompiledAnewAndReplacedNeverTrusted) {
  fs::path cache = scratchDir("cache-bad");
  std::string previous = std::getenv("AOREPLAY_SHADER_CACHE") ? std::getenv("AOREPLAY_SHADER_CACHE") : "";
  ::setenv("AOREPLAY_SHADER_CACHE", cache.c_str(), 1);
  auto specOf = [](const std::string& name, const std::string& value) {
    std::string shader = "#version 450\n#include \"aoreplay.glsl\"\nvoid main() { imageStore(out_ao, ivec2(gl_GlobalInvocationID.xy), vec4(" +
                         value + ")); }\n";
    return loadUserTechniqueSpec(writeTechnique(name, onePassJson(name, "", "[]"), {{"shade.comp", shader}}), "technique.json");
  };
  auto spec = specOf("cachebad", "0.5"), other = specOf("cacheother", "0.25");
  auto entries = [&] {
    std::vector<fs::path> all;
    for (const auto& e : fs::directory_iterator(cache)) all.push_back(e.path());
    return all;
  };
  const auto cold = compileUserPass(spec, 0);
  ASSERT_EQ(entries().size(), 1u);
  const fs::path entry = entries()[0];
  const auto otherCold = compileUserPass(other, 0);
  ASSERT_EQ(entries().size(), 2u);
  const fs::path otherEntry = entries()[0] == entry ? entries()[1] : entries()[0];
  ASSERT_NE(cold.spirv, otherCold.spirv);
  const std::string good = readText(entry);

  auto expectRecompiled = [&](const std::string& what) {
    auto again = compileUserPass(spec, 0);
    EXPECT_FALSE(again.fromCache) << what;
    EXPECT_EQ(again.spirv, cold.spirv) << what;
    EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(entry))) << what;
    EXPECT_EQ(readText(entry), good) << what << ": the entry is replaced by a good one";
    EXPECT_TRUE(compileUserPass(spec, 0).fromCache) << what;
  };
  fs::remove(entry);
  ASSERT_EQ(::mkfifo(entry.c_str(), 0600), 0);
  expectRecompiled("a FIFO");
  fs::remove(entry);
  fs::create_symlink("/dev/zero", entry);
  expectRecompiled("a link to /dev/zero");
  writeFile(entry, good.substr(0, good.size() - 6));
  expectRecompiled("a torn entry");
  std::string flipped = good;
  flipped[flipped.size() - 40] ^= 0x5a;
  writeFile(entry, flipped);
  expectRecompiled("one byte of its SPIR-V changed");
  fs::copy_file(otherEntry, entry, fs::copy_options::overwrite_existing);
  expectRecompiled("another shader's entry under this key");
  ::setenv("AOREPLAY_SHADER_CACHE", previous.c_str(), 1);
}

// Errors inside #included files name the included file and its line; an include outside the
// technique's folder is refused like a shader path.
TEST(UserTechniqueCache, ErrorsInIncludesNameTheIncludedFileAndIncludesStayInTheFolder) {
  auto compileError = [](const std::string& shader, const std::map<std::string, std::string>& files) {
    std::map<std::string, std::string> all = files;
    all["shade.comp"] = shader;
    auto file = writeTechnique("include-errors", onePassJson("includes", "", "[]"), all);
    auto spec = loadUserTechniqueSpec(file, "technique.json");
    try {
      compileUserPass(spec, 0);
    } catch (const InputError& e) {
      EXPECT_EQ(e.field, "passes[0].shader");
      return std::string(e.what());
    }
    return std::string("compiled");
  };
  std::string head = "#version 450\n#include \"aoreplay.glsl\"\n";
  std::string body = "void main() { imageStore(out_ao, ivec2(gl_GlobalInvocationID.xy), vec4(kValue)); }\n";
  std::string message = compileError(head + "#include \"lib/value.glsl\"\n" + body, {{"lib/value.glsl", "// value\nconst float kValue = ;\n"}});
  EXPECT_NE(message.find("lib/value.glsl:2: error"), std::string::npos) << message;
  message = compileError(head + "#include \"../outside.glsl\"\n" + body, {});
  EXPECT_NE(message.find("shade.comp:3: error"), std::string::npos) << message;
  EXPECT_NE(message.find("leaves the technique's folder"), std::string::npos) << message;
}

// History, seed 000's denoisers, a half-scale write and an enum parameter, replayed in process: the
// output is half of last frame's final visibility (history holds 1.0 while it is invalid), so
// frames 0, 1, 2 of a static capture give 0.5, 0.25, 0.125 with the denoisers off (spatial=0,
// temporal=0), and 1 throughout with mode=keep.
const char* kHistoryJson = R"({"format": "aoreplay-technique", "version": 1, "name": "halving",
  "parameters": {"mode": {"type": "enum", "choices": ["halve", "keep"], "default": "halve"}},
  "passes": [
    {"name": "coarse", "shader": "coarse.comp", "reads": ["depth"], "writes": [{"name": "coarse", "format": "r32f", "scale": "half"}],
     "workgroup": [4, 4]},
    {"name": "halve", "shader": "halve.comp", "reads": ["history", "coarse"], "writes": [{"name": "ao", "format": "r16f"}]}],
  "output": "ao", "denoise": "seed000"})";
const char* kCoarseShader = R"(#version 450
#include "aoreplay.glsl"
void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(vec2(pixel), frame.size))) return;
  imageStore(out_coarse, pixel, vec4(frame.size.x));  // the half size, to show it
}
)";
const char* kHalveShader = R"(#version 450
#include "aoreplay.glsl"
void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(vec2(pixel), frame.size))) return;
  float previous = texelFetch(in_history, pixel, 0).r;
  float halfWidth = texelFetch(in_coarse, pixel / 2, 0).r;
  bool halfScale = halfWidth == floor((frame.size.x + 1.0) / 2.0);
  float v = params.mode == 0 ? previous * 0.5 : previous;
  imageStore(out_ao, pixel, vec4(halfScale ? v : 0.0));
}
)";

TEST(UserTechniqueFeatures, HistoryHalfScaleSeed000AndEnumReplayAsDeclared) {
  auto file = writeTechnique("halving", kHistoryJson, {{"coarse.comp", kCoarseShader}, {"halve.comp", kHalveShader}});
  auto capture = generatedCapture("boxes", "static", 33, 19, 3);  // odd: half scale rounds up
  auto frames = replayWithSettings(capture, file.string(), {"spatial=0", "temporal=0"}).frames;
  ASSERT_EQ(frames.size(), 3u);
  for (size_t f = 0; f < 3; ++f) {
    float expected = f == 0 ? 0.5f : f == 1 ? 0.25f : 0.125f;
    EXPECT_EQ(frames[f].visibility.front(), expected) << "frame " << f;
    EXPECT_EQ(frames[f].visibility.back(), expected) << "frame " << f;
  }
  auto kept = replayWithSettings(capture, file.string(), {"mode=keep", "spatial=0", "temporal=0"}).frames;
  EXPECT_EQ(kept[2].visibility.front(), 1.0f);
  // With seed 000's temporal blend on, the run validates clean and replays bit-identically.
  fs::path a = scratchDir("halving-a") / "out", b = scratchDir("halving-b") / "out";
  for (const auto& out : {a, b}) {
    auto r = runAoreplay(fmt::format("run {} --technique {} --validate --out {}", capture.string(), file.string(), out.string()));
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("validation: 0 messages"), std::string::npos) << r.output;
  }
  for (int f = 0; f < 3; ++f) {
    auto name = fmt::format("{:04}.exr", f);
    EXPECT_EQ(readText(a / "ao" / name), readText(b / "ao" / name)) << name;
  }
}

// user_techniques/FORMAT.md's example: its JSON block and GLSL blocks written out and replayed.
TEST(FormatDoc, TheExampleCompilesAndRunsValidated) {
  std::string doc = readText(fs::path(AOR_SOURCE_DIR) / "user_techniques" / "FORMAT.md");
  std::string section = doc.substr(doc.find("\n## Example"));
  section = section.substr(0, section.find("\n## ", 1));
  fs::path dir = scratchDir("format-doc");
  std::regex block("```(json|glsl)\\n([\\s\\S]*?)```");
  int jsonBlocks = 0, glslBlocks = 0;
  for (std::sregex_iterator it(section.begin(), section.end(), block), end; it != end; ++it) {
    std::string text = (*it)[2];
    if ((*it)[1] == "json") {
      writeFile(dir / "technique.json", text);
      ++jsonBlocks;
    } else {
      ASSERT_EQ(text.rfind("// ", 0), 0u) << text;
      writeFile(dir / text.substr(3, text.find('\n') - 3), text);
      ++glslBlocks;
    }
  }
  ASSERT_EQ(jsonBlocks, 1);
  ASSERT_EQ(glslBlocks, 2);
  fs::path out = dir / "out";
  auto r = runAoreplay(fmt::format("run {} --technique {} --frames 0:2 --validate --out {}", shipped("boxes-strafe").string(),
                                   (dir / "technique.json").string(), out.string()));
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("validation: 0 messages"), std::string::npos) << r.output;
  json report = json::parse(std::ifstream(out / "report.json"));
  EXPECT_EQ(report["settings"]["technique"], "my_ssao");
}

}  // namespace
}  // namespace aor::test
