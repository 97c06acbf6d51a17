// Issue 44, class 2: a user technique past a limit of the selected device (push descriptors,
// shared memory, the params block, timestamp slots) is refused before any GPU work with exit 2
// naming the pass, the limit and the value; before, lavapipe crashed or ran invalid Vulkan. A
// technique of 100 chained passes replays with its report. exceededLimit is also checked against
// each limit of a made-up device, and the shared-memory size reflection against a known shader.
#include <fstream>
#include <regex>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "gpu_test_support.h"
#include "techniques/user/shader_compiler.h"
#include "techniques/user/user_technique_spec.h"
#include "vk/device_limits.h"
#include "vk/shader_reflection.h"

namespace aor::test {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

void writeFile(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

const char* kPrelude = "#version 450\n#include \"aoreplay.glsl\"\n";

// A technique of `count` chained passes: p0 writes a0 from linear depth, pass i copies a(i-1) to a(i).
// `firstBody` replaces p0's shader body (after the prelude).
fs::path chainTechnique(const std::string& name, size_t count, const std::string& firstBody = "") {
  fs::path dir = scratchDir(name);
  json passes = json::array();
  for (size_t i = 0; i < count; ++i) {
    json reads = i == 0 ? json::array({"linear_depth"}) : json::array({fmt::format("a{}", i - 1)});
    passes.push_back({{"name", fmt::format("p{}", i)}, {"shader", fmt::format("p{}.comp", i)}, {"reads", reads},
                      {"writes", json::array({{{"name", fmt::format("a{}", i)}, {"format", "r16f"}}})}});
    std::string body = i == 0 ? (firstBody.empty() ? "void main() { ivec2 p = ivec2(gl_GlobalInvocationID.xy);\n"
                                                     "  imageStore(out_a0, p, vec4(texelFetch(in_linear_depth, p, 0).r > 0.0 ? 0.5 : 1.0)); }\n"
                                                   : firstBody)
                              : fmt::format("void main() {{ ivec2 p = ivec2(gl_GlobalInvocationID.xy); imageStore(out_a{}, p, texelFetch(in_a{}, p, 0)); }}\n",
                                            i, i - 1);
    writeFile(dir / fmt::format("p{}.comp", i), kPrelude + body);
  }
  json doc = {{"format", "aoreplay-technique"}, {"version", 1}, {"name", name}, {"passes", passes}, {"output", fmt::format("a{}", count - 1)}};
  writeFile(dir / "technique.json", doc.dump(1));
  return dir / "technique.json";
}

struct Refusal {
  CommandResult result;
  fs::path out, cache;
};
Refusal runRefused(const fs::path& technique, const std::string& tag) {
  Refusal r;
  r.out = scratchDir("out-" + tag) / "out";
  r.cache = scratchDir("cache-" + tag);
  r.result = runAoreplay(fmt::format("run {}/captures/boxes-orbit --technique {} --frames 0:1 --out {}", AOR_SOURCE_DIR,
                                     technique.string(), r.out.string()),
                         "AOREPLAY_SHADER_CACHE=" + r.cache.string());
  EXPECT_EQ(r.result.exitCode, 2) << r.result.output;
  EXPECT_FALSE(fs::exists(r.out)) << "nothing is written by a refused run";
  return r;
}

TEST(TechniqueLimits, APassWith65StorageWritesIsRefusedNamingThePassAndThePushDescriptorLimit) {
  fs::path dir = scratchDir("wide");
  json writes = json::array({{{"name", "ao"}, {"format", "r16f"}}});
  std::string stores;
  for (int i = 0; i < 64; ++i) {
    writes.push_back({{"name", fmt::format("w{}", i)}, {"format", "r16f"}});
    stores += fmt::format("  imageStore(out_w{}, p, vec4(0));\n", i);
  }
  json reads = json::array({"ao"});
  for (int i = 0; i < 64; ++i) reads.push_back(fmt::format("w{}", i));
  json doc = {{"format", "aoreplay-technique"}, {"version", 1}, {"name", "wide"}, {"output", "out"},
              {"passes", json::array({{{"name", "wide"}, {"shader", "wide.comp"}, {"reads", json::array({"linear_depth"})}, {"writes", writes}},
                                      {{"name", "gather"}, {"shader", "gather.comp"}, {"reads", reads},
                                       {"writes", json::array({{{"name", "out"}, {"format", "r16f"}}})}}})}};
  writeFile(dir / "technique.json", doc.dump(1));
  writeFile(dir / "wide.comp", kPrelude + std::string("void main() { ivec2 p = ivec2(gl_GlobalInvocationID.xy);\n  imageStore(out_ao, p, vec4(1));\n") +
                                   stores + "}\n");
  writeFile(dir / "gather.comp", kPrelude + std::string("void main() { ivec2 p = ivec2(gl_GlobalInvocationID.xy); "
                                                        "imageStore(out_out, p, texelFetch(in_ao, p, 0)); }\n"));
  auto r = runRefused(dir / "technique.json", "wide");
  EXPECT_TRUE(std::regex_search(r.result.output, std::regex(R"(field "passes\[0\]": pass 'wide' needs 67 push descriptors \(the device allows \d+\) on device ')")))
      << r.result.output;
}

TEST(TechniqueLimits, SixtyFourMiBOfSharedMemoryIsRefusedNamingThePass) {
  auto technique = chainTechnique("shared", 2,
                                  "shared float big[16777216];\n"
                                  "void main() { big[gl_LocalInvocationIndex] = 1.0; barrier();\n"
                                  "  imageStore(out_a0, ivec2(gl_GlobalInvocationID.xy), vec4(big[0])); }\n");
  auto r = runRefused(technique, "shared");
  EXPECT_TRUE(std::regex_search(r.result.output, std::regex(R"(passes\[0\]": pass 'p0' needs 67108864 bytes of shared memory \(the device allows \d+\))")))
      << r.result.output;
}

TEST(TechniqueLimits, AParamsBlockPastVkCmdUpdateBuffersLimitIsRefusedAtLoad) {
  auto technique = chainTechnique("params", 1);
  json doc = json::parse(readText(technique));
  json parameters = json::object();
  for (int i = 0; i < 17000; ++i) parameters[fmt::format("k{}", i)] = {{"type", "float"}, {"default", 1}, {"min", 0}, {"max", 2}};
  doc["parameters"] = parameters;
  writeFile(technique, doc.dump());
  auto r = runRefused(technique, "params");
  EXPECT_NE(r.result.output.find("field \"parameters\": 17000 parameters make a params block of 68000 bytes; at most 16384"), std::string::npos)
      << r.result.output;
}

TEST(TechniqueLimits, MorePassesThanTimestampSlotsAreRefusedBeforeAnyShaderIsCompiled) {
  auto r = runRefused(chainTechnique("chain300", 300), "chain300");
  EXPECT_NE(r.result.output.find("field \"passes\": 300 passes; a technique has at most 200"), std::string::npos) << r.result.output;
  EXPECT_TRUE(!fs::exists(r.cache) || fs::is_empty(r.cache)) << "no shader was compiled";
}

TEST(TechniqueLimits, AHundredChainedPassesReplayWithTheirReport) {
  fs::path out = scratchDir("chain100-out") / "out";
  auto r = runAoreplay(fmt::format("run {}/captures/boxes-orbit --technique {} --frames 0:1 --out {}", AOR_SOURCE_DIR,
                                   chainTechnique("chain100", 100).string(), out.string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  json report = json::parse(readText(out / "report.json"));
  size_t chained = 0;
  for (const auto& pass : report["passes"]) chained += std::regex_match(pass["name"].get<std::string>(), std::regex(R"(p\d+)"));
  EXPECT_EQ(chained, 100u);
  const std::string html = readText(out / "report.html");
  EXPECT_NE(html.find("drawn as a list in execution order"), std::string::npos);
  EXPECT_NE(html.find("] p99</text>"), std::string::npos);
}

TEST(TechniqueLimits, EachLimitIsNamedWithItsValueAndTheDevicesFigure) {
  DeviceLimits limits;
  limits.maxPushDescriptors = limits.maxPerStageResources = 8;
  limits.maxPerStageStorageImages = limits.maxPerStageSampledImages = limits.maxPerStageSamplers = 4;
  limits.maxPerStageUniformBuffers = limits.maxPerStageStorageBuffers = 2;
  limits.maxPushConstantsSize = 128;
  limits.maxComputeSharedMemorySize = 1024;
  limits.maxComputeWorkGroupSize = {64, 32, 1};
  limits.maxComputeWorkGroupInvocations = 256;
  auto shaderWith = [](std::initializer_list<std::pair<VkDescriptorType, int>> kinds) {
    ShaderInterface s;
    for (auto [type, n] : kinds)
      for (int i = 0; i < n; ++i) s.bindings.push_back({type, false, "b"});
    return s;
  };
  const std::array<uint32_t, 3> small{8, 8, 1};
  EXPECT_EQ(exceededLimit(shaderWith({{VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 4}}), small, limits), std::nullopt);
  EXPECT_EQ(exceededLimit(shaderWith({{VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, 9}}), small, limits), "9 push descriptors (the device allows 8)");
  EXPECT_EQ(exceededLimit(shaderWith({{VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 5}}), small, limits), "5 storage images (the device allows 4)");
  EXPECT_EQ(exceededLimit(shaderWith({{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 5}}), small, limits), "5 sampled images (the device allows 4)");
  EXPECT_EQ(exceededLimit(shaderWith({{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 3}}), small, limits), "3 uniform buffers (the device allows 2)");
  EXPECT_EQ(exceededLimit(shaderWith({{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 3}}), small, limits), "3 storage buffers (the device allows 2)");
  ShaderInterface s;
  s.pushConstantBytes = 132;
  EXPECT_EQ(exceededLimit(s, small, limits), "132 bytes of push constants (the device allows 128)");
  s = {};
  s.workgroupMemoryBytes = 1028;
  EXPECT_EQ(exceededLimit(s, small, limits), "1028 bytes of shared memory (the device allows 1024)");
  EXPECT_EQ(exceededLimit({}, {8, 64, 1}, limits), "64 invocations in a workgroup's y (the device allows 32)");
  EXPECT_EQ(exceededLimit({}, {32, 32, 1}, limits), "1024 invocations in a workgroup (the device allows 256)");
}

TEST(TechniqueLimits, SharedMemoryIsReflectedAtItsNaturalSize) {
  auto file = chainTechnique("reflect", 1,
                             "struct Pair { vec3 a; float b; };\n"
                             "shared float row[64];\nshared vec4 tile[16];\nshared Pair pairs[4];\nshared mat3 m;\n"
                             "void main() { row[0] = 1.0; tile[0] = vec4(1); pairs[0].b = 1.0; m[0][0] = 1.0; barrier();\n"
                             "  imageStore(out_a0, ivec2(gl_GlobalInvocationID.xy), vec4(row[0] + tile[0].x + pairs[0].b + m[0][0])); }\n");
  auto spec = loadUserTechniqueSpec(file, "technique.json");
  ShaderInterface iface = reflectComputeShader(compileUserPass(spec, 0).spirv, "reflect");
  EXPECT_EQ(iface.workgroupMemoryBytes, 64u * 4 + 16u * 16 + 4u * 16 + 36u);
}

}  // namespace
}  // namespace aor::test
