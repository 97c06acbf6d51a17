// The graph's capacity beyond one-level images, on lavapipe with validation (tests/graph/
// subresource_test.cpp checks the same shapes without a GPU): two test-only techniques, registered
// here and never shown to users. test_mip_chain writes a 5-level mip chain (level by level through
// single-level views, or all levels in one dispatch through one binding per level) and reads it
// back through one sampler; test_buffer clears a storage buffer, counts into it with atomics and
// reads it as a uniform buffer. Every level and the counts are checked against the CPU.
#include <cmath>
#include <fstream>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "embedded_shaders.h"
#include "gpu_test_support.h"
#include "runtime/pass_context.h"
#include "report/run_outputs.h"
#include "vk/vk_check.h"
#include "test_graph.h"

namespace aor::spirv {
std::span<const EmbeddedShader> aor_test_shaders();  // tests/support/shaders/, generated index
}  // namespace aor::spirv

namespace aor::test {
namespace {

namespace fs = std::filesystem;
constexpr uint32_t kLevels = 5;

ShaderCode testShader(const std::string& name) { return {name, spirv::code(name, spirv::aor_test_shaders())}; }

shader::TestGraphConstants constantsFor(uint32_t w, uint32_t h, int level) {
  shader::TestGraphConstants c{};
  c.size = {int(w), int(h)};
  c.level = level;
  return c;
}

void addMipChainPasses(FrameBuilder& frame, const Settings& settings) {
  auto& g = frame.graph();
  auto& pipelines = frame.pipelines();
  uint32_t w = frame.size().x, h = frame.size().y;
  auto chain = g.createImage("test_chain", {w, h, VK_FORMAT_R32_SFLOAT, kLevels});
  auto distance = frame.linearDistance();
  g.addPass(
      "chain_base",
      [&](graph::PassBuilder& b) {
        b.read(distance, graph::Access::StorageRead);
        b.write(chain, graph::Access::StorageWrite, graph::Subresources::mip(0));
      },
      [&pipelines, distance, chain, w, h](graph::PassContext& ctx) {
        auto c = constantsFor(w, h, 0);
        dispatchCompute(ctx, pipelines.get(testShader("test_mip_base")), {distance, {chain, graph::Subresources::mip(0)}}, &c, w, h);
      });
  auto levelSize = [&](uint32_t level) { return glm::uvec2(std::max(1u, w >> level), std::max(1u, h >> level)); };
  if (settings.text("build") == "minify") {
    for (uint32_t level = 1; level < kLevels; ++level) {
      glm::uvec2 size = levelSize(level);
      g.addPass(
          "chain_minify",
          [&](graph::PassBuilder& b) {
            b.read(chain, graph::Access::SampledRead, graph::Subresources::mip(level - 1));
            b.write(chain, graph::Access::StorageWrite, graph::Subresources::mip(level));
          },
          [&pipelines, chain, level, size](graph::PassContext& ctx) {
            auto c = constantsFor(size.x, size.y, int(level));
            dispatchCompute(ctx, pipelines.get(testShader("test_mip_minify")),
                            {{chain, graph::Subresources::mip(level - 1)}, {chain, graph::Subresources::mip(level)}}, &c,
                            size.x, size.y);
          });
    }
  } else {
    glm::uvec2 size = levelSize(1);
    g.addPass(
        "chain_subsample",
        [&](graph::PassBuilder& b) {
          b.read(chain, graph::Access::StorageRead, graph::Subresources::mip(0));
          b.write(chain, graph::Access::StorageWrite, {1, kLevels - 1});
        },
        [&pipelines, chain, size](graph::PassContext& ctx) {
          auto c = constantsFor(size.x, size.y, 1);
          using graph::Subresources;
          dispatchCompute(ctx, pipelines.get(testShader("test_mip_subsample")),
                          {{chain, Subresources::mip(0)}, {chain, Subresources::mip(1)}, {chain, Subresources::mip(2)},
                           {chain, Subresources::mip(3)}, {chain, Subresources::mip(4)}},
                          &c, size.x, size.y);
        });
  }
  auto out = g.createImage("test_visibility", {w, h, VK_FORMAT_R16_SFLOAT});
  g.addPass(
      "chain_use",
      [&](graph::PassBuilder& b) {
        b.read(chain, graph::Access::SampledRead);
        b.write(out);
      },
      [&pipelines, chain, out, w, h](graph::PassContext& ctx) {
        auto c = constantsFor(w, h, int(kLevels - 1));
        dispatchCompute(ctx, pipelines.get(testShader("test_mip_use")), {chain, out}, &c, w, h);
      });
  for (uint32_t level = 0; level < kLevels; ++level)
    frame.debugView(fmt::format("mip{}", level), chain, graph::Subresources{level, 1, 0, 1});
  frame.setOutput(out, OutputLayout::visibilityOnly());
}

void addBufferPasses(FrameBuilder& frame, const Settings&) {
  auto& g = frame.graph();
  auto& pipelines = frame.pipelines();
  uint32_t w = frame.size().x, h = frame.size().y;
  auto counter = g.createBuffer("test_counter", {2 * sizeof(uint32_t)});
  auto distance = frame.linearDistance();
  auto out = g.createImage("test_visibility", {w, h, VK_FORMAT_R16_SFLOAT});
  g.addPass(
      "clear_counter", [&](graph::PassBuilder& b) { b.write(counter, graph::Access::ClearWrite); },
      [counter](graph::PassContext& ctx) { vkCmdFillBuffer(ctx.cmd, ctx.buffer(counter).buffer, 0, VK_WHOLE_SIZE, 0); });
  g.addPass(
      "count_sky",
      [&](graph::PassBuilder& b) {
        b.read(distance, graph::Access::StorageRead);
        b.read(counter, graph::Access::StorageRead);
        b.write(counter, graph::Access::StorageWrite);
      },
      [&pipelines, distance, counter, w, h](graph::PassContext& ctx) {
        auto c = constantsFor(w, h, 0);
        dispatchCompute(ctx, pipelines.get(testShader("test_buffer_count")), {distance, counter}, &c, w, h);
      });
  g.addPass(
      "use_counter",
      [&](graph::PassBuilder& b) {
        b.read(counter, graph::Access::UniformRead);
        b.write(out);
      },
      [&pipelines, counter, out, w, h](graph::PassContext& ctx) {
        auto c = constantsFor(w, h, 0);
        dispatchCompute(ctx, pipelines.get(testShader("test_buffer_use")), {counter, out}, &c, w, h);
      });
  frame.debugView("counter", counter);
  frame.setOutput(out, OutputLayout::visibilityOnly());
}

Technique testTechnique(std::string name, std::function<void(FrameBuilder&, const Settings&)> passes) {
  Technique t;
  t.name = std::move(name);
  t.summary = "test only: exercises the graph's mip levels and buffers";
  t.testOnly = true;
  t.addPasses = std::move(passes);
  return t;
}

const Technique& mipChainTechnique() {
  static const Technique t = [] {
    Technique m = testTechnique("test_mip_chain", addMipChainPasses);
    m.parameters = {enumParameter("build", {"minify", "subsample"}, 0, "levels one by one, or all in one dispatch")};
    for (uint32_t level = 0; level < kLevels; ++level) m.debugViews.push_back({fmt::format("mip{}", level), "one level"});
    return m;
  }();
  return t;
}

const Technique& bufferTechnique() {
  static const Technique t = [] {
    Technique b = testTechnique("test_buffer", addBufferPasses);
    b.debugViews = {{"counter", "sky pixels, all pixels"}};
    return b;
  }();
  return t;
}

// Registered in every test process (CTest runs each test as its own process).
const bool kRegistered = [] {
  registerTechnique(&mipChainTechnique());
  registerTechnique(&bufferTechnique());
  return true;
}();

struct ReplayedWithViews {
  std::vector<FrameOutput> frames;
  ReplayResult result;
};

ReplayedWithViews replayWithViews(const fs::path& path, const Settings& settings, std::set<std::string> views) {
  Capture capture = loadCapture(path);
  ReplayOptions options(settings);
  options.debugViews = std::move(views);
  ReplayedWithViews out;
  out.result = replayCapture(validatedContext(), capture, options, [&](const FrameOutput& f) { out.frames.push_back(f); });
  return out;
}

const DebugImage& view(const FrameOutput& f, const std::string& name) {
  for (const auto& d : f.debugImages)
    if (d.name == name) return d;
  throw std::runtime_error("no debug view " + name);
}

// Level k of a chain as the minify shader computes it: the mean of each 2x2 block, edges clamped.
std::vector<float> minify(const std::vector<float>& finer, int fw, int fh, int w, int h) {
  std::vector<float> out(size_t(w) * size_t(h));
  auto at = [&](int x, int y) { return finer[size_t(std::min(y, fh - 1)) * size_t(fw) + size_t(std::min(x, fw - 1))]; };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      out[size_t(y) * size_t(w) + size_t(x)] =
          ((at(2 * x, 2 * y) + at(2 * x + 1, 2 * y)) + (at(2 * x, 2 * y + 1) + at(2 * x + 1, 2 * y + 1))) * 0.25f;
  return out;
}

std::vector<float> subsample(const std::vector<float>& level0, int w0, int level, int w, int h) {
  std::vector<float> out(size_t(w) * size_t(h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) out[size_t(y) * size_t(w) + size_t(x)] = level0[size_t(y << level) * size_t(w0) + size_t(x << level)];
  return out;
}

class MipChain : public ::testing::TestWithParam<std::string> {};

TEST_P(MipChain, EveryLevelIsWrittenReadBackAndSampledAsTheCpuComputesIt) {
  auto path = generatedCapture("boxes", "orbit", 64, 36, 1);
  Settings settings(mipChainTechnique());
  settings.assign("build", GetParam());
  std::set<std::string> views;
  for (uint32_t level = 0; level < kLevels; ++level) views.insert(fmt::format("mip{}", level));
  auto replayed = replayWithViews(path, settings, views);
  ASSERT_EQ(replayed.frames.size(), 1u);
  const auto& frame = replayed.frames[0];
  const auto& base = view(frame, "mip0");
  ASSERT_EQ(base.width, 64);
  ASSERT_EQ(base.height, 36);
  float maxDistance = *std::max_element(base.values.begin(), base.values.end());
  EXPECT_GT(maxDistance, 1.0f) << "level 0 holds the scene's distances, not zeros";

  std::vector<std::vector<float>> expected{base.values};
  for (uint32_t level = 1; level < kLevels; ++level) {
    const auto& got = view(frame, fmt::format("mip{}", level));
    int w = std::max(1, 64 >> level), h = std::max(1, 36 >> level);
    ASSERT_EQ(got.width, w) << "level " << level;
    ASSERT_EQ(got.height, h) << "level " << level;
    int fw = std::max(1, 64 >> (level - 1)), fh = std::max(1, 36 >> (level - 1));
    expected.push_back(GetParam() == "minify" ? minify(expected.back(), fw, fh, w, h) : subsample(base.values, 64, int(level), w, h));
    double worst = 0;
    for (size_t i = 0; i < got.values.size(); ++i)
      worst = std::max(worst, double(std::abs(got.values[i] - expected.back()[i])) / std::max(1.0f, std::abs(expected.back()[i])));
    EXPECT_LE(worst, 1e-6) << "level " << level;
  }
  // The use pass read every level through one view of the whole chain.
  double worst = 0;
  for (int y = 0; y < 36; ++y)
    for (int x = 0; x < 64; ++x) {
      double sum = 0;
      for (uint32_t k = 0; k < kLevels; ++k) {
        int w = std::max(1, 64 >> k), h = std::max(1, 36 >> k);
        sum += expected[k][size_t(std::min(y >> k, h - 1)) * size_t(w) + size_t(std::min(x >> k, w - 1))];
      }
      worst = std::max(worst, std::abs(double(frame.visibility[size_t(y) * 64 + size_t(x)]) - 1.0 / (1.0 + sum)));
    }
  EXPECT_LE(worst, 1e-3) << "half-float output";
  // Built as declared: the per-level variant runs four minify passes, the other one dispatch.
  int minifyPasses = 0;
  for (const auto& p : replayed.result.frames[0].passes) minifyPasses += p.name == "chain_minify";
  EXPECT_EQ(minifyPasses, GetParam() == "minify" ? 4 : 0);
}

INSTANTIATE_TEST_SUITE_P(Builds, MipChain, ::testing::Values("minify", "subsample"));

TEST(StorageBuffer, IsClearedCountedIntoWithAtomicsAndReadAsAUniformBuffer) {
  auto path = generatedCapture("boxes", "orbit", 64, 36, 2);
  Capture capture = loadCapture(path);
  auto replayed = replay(path, Settings(bufferTechnique()));
  ASSERT_EQ(replayed.frames.size(), 2u);
  for (const auto& frame : replayed.frames) {
    GBuffer g = loadGBuffer(capture, frame.index);
    size_t sky = 0;
    for (float d : g.depth) sky += d >= 1.0f;  // the generator's sky is the far plane (standard depth)
    ASSERT_GT(sky, 0u);
    ASSERT_LT(sky, g.depth.size());
    double expected = 1.0 - double(sky) / double(g.depth.size());
    for (float v : frame.visibility) ASSERT_NEAR(v, expected, 1e-3) << "frame " << frame.index;
  }
  // Frame 1's counts are its own: without the clear it would see frame 0's added to them.
}

TEST(StorageBuffer, CountsReadBackAsADebugViewLandInTheReport) {
  auto path = generatedCapture("boxes", "orbit", 64, 36, 2);
  Capture capture = loadCapture(path);
  ReplayOptions options{Settings(bufferTechnique())};
  options.debugViews = {"counter"};
  auto result = replayCapture(validatedContext(), capture, options, nullptr);
  ASSERT_EQ(result.frames.size(), 2u);
  auto report = buildReport(capture, options, result);
  for (const auto& f : result.frames) {
    GBuffer g = loadGBuffer(capture, f.index);
    uint32_t sky = 0;
    for (float d : g.depth) sky += d >= 1.0f;
    const auto& counts = report["frames"][size_t(f.index)]["debug"]["counter"];
    ASSERT_EQ(counts.size(), 2u) << report["frames"][size_t(f.index)].dump();
    EXPECT_EQ(counts[0].get<uint32_t>(), sky) << "frame " << f.index;
    EXPECT_EQ(counts[1].get<uint32_t>(), uint32_t(g.depth.size()));
  }
}

// A device feature a technique asks for and the device lacks: the replay refuses before any GPU work
// with NoDeviceError (the CLI's exit 3) naming the extension.
TEST(DeviceFeatures, AMissingExtensionIsRefusedNamingIt) {
  static const Technique needy = [] {
    Technique t = testTechnique("test_needs_extension", addBufferPasses);
    t.missingDeviceExtensions = [](const Settings&, const DeviceInfo& device) {
      std::vector<std::string> missing;
      for (const char* e : {"VK_KHR_push_descriptor", "VK_AOR_not_an_extension"})
        if (!device.hasExtension(e)) missing.push_back(e);
      return missing;
    };
    return t;
  }();
  auto capture = loadCapture(generatedCapture("boxes", "orbit", 64, 36, 1));
  ReplayOptions options{Settings(needy)};
  try {
    replayCapture(validatedContext(), capture, options, nullptr);
    FAIL() << "a technique needing a missing extension ran";
  } catch (const NoDeviceError& e) {
    std::string what = e.what();
    EXPECT_NE(what.find("needs VK_AOR_not_an_extension, which device"), std::string::npos) << what;
    EXPECT_EQ(what.find("VK_KHR_push_descriptor"), std::string::npos) << "the device has that one: " << what;
  }
}

}  // namespace
}  // namespace aor::test
