// Formats, describe() text and Graphviz output (validated with `dot` when it is installed).
#include <string>

#include "graph_test_support.h"

namespace aor::graph::testing {
namespace {

::testing::AssertionResult Contains(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "text does not contain '" << part << "':\n" << text;
}

TEST(GraphFormats, BytesPerPixelAndNames) {
  struct Case {
    VkFormat format;
    uint32_t bytes;
    const char* name;
  };
  const Case cases[] = {
      {VK_FORMAT_R8_UNORM, 1, "R8_UNORM"},
      {VK_FORMAT_R8G8_UNORM, 2, "R8G8_UNORM"},
      {VK_FORMAT_R16_SFLOAT, 2, "R16_SFLOAT"},
      {VK_FORMAT_R16G16_SFLOAT, 4, "R16G16_SFLOAT"},
      {VK_FORMAT_R32_SFLOAT, 4, "R32_SFLOAT"},
      {VK_FORMAT_R8G8B8A8_UNORM, 4, "R8G8B8A8_UNORM"},
      {VK_FORMAT_A2B10G10R10_UNORM_PACK32, 4, "A2B10G10R10_UNORM_PACK32"},
      {VK_FORMAT_R16G16B16A16_SFLOAT, 8, "R16G16B16A16_SFLOAT"},
      {VK_FORMAT_R32G32_SFLOAT, 8, "R32G32_SFLOAT"},
      {VK_FORMAT_R32G32B32A32_SFLOAT, 16, "R32G32B32A32_SFLOAT"},
  };
  for (const Case& c : cases) {
    EXPECT_EQ(bytesPerPixel(c.format), c.bytes) << c.name;
    EXPECT_STREQ(formatName(c.format), c.name);
  }
  EXPECT_EQ(bytesPerPixel(VK_FORMAT_UNDEFINED), 0u);
  EXPECT_EQ(bytesPerPixel(VK_FORMAT_BC7_UNORM_BLOCK), 0u);
  EXPECT_EQ(imageBytes({1920, 1080, VK_FORMAT_R16G16B16A16_SFLOAT}), 1920ull * 1080 * 8);
  EXPECT_EQ(imageBytes({100000, 100000, VK_FORMAT_R32G32B32A32_SFLOAT}), 160000000000ull)
      << "no 32-bit overflow";
}

TEST(GraphNames, FlagsAndLayouts) {
  EXPECT_EQ(stageNames(VK_PIPELINE_STAGE_2_NONE), "NONE");
  EXPECT_EQ(stageNames(VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT),
            "COMPUTE_SHADER|COPY");
  EXPECT_EQ(accessNames(VK_ACCESS_2_SHADER_SAMPLED_READ_BIT), "SHADER_SAMPLED_READ");
  EXPECT_STREQ(layoutName(VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL), "SHADER_READ_ONLY_OPTIMAL");
  EXPECT_STREQ(kindName(ResourceKind::History), "history");
  EXPECT_STREQ(accessName(Access::TransferRead), "transfer read");
}

TEST(GraphDescribe, ExplainsRunAndCulledPassesResourcesAndTotals) {
  Pipeline p = buildPipeline({.edgeWeights = true, .readback = Readback::Noisy});
  const CompiledGraph c = p.graph.compile();
  checkCompiled(p.graph, c);
  const std::string text = describe(p.graph, c);
  EXPECT_TRUE(Contains(text, "passes run:"));
  EXPECT_TRUE(Contains(text, "passes culled:"));
  EXPECT_TRUE(Contains(text, "resources:"));
  ASSERT_EQ(c.culled.size(), 3u);
  for (const CulledPass& cp : c.culled) {
    EXPECT_TRUE(Contains(text, p.graph.passes()[cp.pass].name + ": " + cp.reason));
  }
  // Passes run, with their accesses and barriers.
  EXPECT_TRUE(Contains(text, "[3] gtao"));
  EXPECT_TRUE(Contains(text, "view_depth (sampled read)"));
  EXPECT_TRUE(Contains(text, "ao_noisy (storage write)"));
  EXPECT_TRUE(Contains(text, "barrier ao_noisy: GENERAL -> TRANSFER_SRC_OPTIMAL, COMPUTE_SHADER -> COPY"));
  // Resources: kind, size, format, lifetime, unused ones.
  EXPECT_TRUE(Contains(text, "depth_raw [imported] 1920x1080 R32_SFLOAT"));
  EXPECT_TRUE(Contains(text, "lifetime gtao .. readback"));
  EXPECT_TRUE(Contains(text, "ao_history.previous [history] 1920x1080 R16G16_SFLOAT"));
  EXPECT_TRUE(Contains(text, "ao_blurred [transient] 1920x1080 R16_SFLOAT, 4147200 bytes (3.96 MiB): "
                             "not allocated (unused)"));
  // Totals with MiB.
  EXPECT_TRUE(Contains(text, "transient (aliased):"));
  EXPECT_TRUE(Contains(text, "transient unaliased:"));
  EXPECT_TRUE(Contains(text, "persistent:          8294400 bytes (7.91 MiB)"));
  EXPECT_TRUE(Contains(text, "peak:"));
}

TEST(GraphDescribe, ShowsAliasing) {
  Pipeline p = buildPipeline();
  const CompiledGraph c = p.graph.compile();
  const std::string text = describe(p.graph, c);
  const int slot = c.resources[p.aoBlurred].memorySlot;
  EXPECT_TRUE(Contains(text, "memory slot " + std::to_string(slot) + " (aliases normals_reconstructed)"));
  EXPECT_TRUE(Contains(text, "memory slot " + std::to_string(slot) + " (aliases ao_blurred)"));
  EXPECT_TRUE(Contains(text, "ao_history.current [history]"));
  EXPECT_TRUE(Contains(text, "persistent"));
}

TEST(GraphDot, StructureAndStyles) {
  Pipeline p = buildPipeline({.readback = Readback::Noisy});
  const CompiledGraph c = p.graph.compile();
  const std::string dot = toDot(p.graph, c);
  EXPECT_EQ(dot.rfind("digraph ", 0), 0u);
  EXPECT_EQ(dot.back(), '\n');
  EXPECT_TRUE(Contains(dot, "shape=box"));
  EXPECT_TRUE(Contains(dot, "shape=ellipse"));
  EXPECT_TRUE(Contains(dot, "style=dashed, color=grey"));              // culled / unused
  EXPECT_TRUE(Contains(dot, "culled: writes ao_blurred"));             // reason on the node
  EXPECT_TRUE(Contains(dot, "r" + std::to_string(p.aoNoisy) + " -> p" + std::to_string(p.readback)));
  EXPECT_TRUE(Contains(dot, "p" + std::to_string(p.gtao) + " -> r" + std::to_string(p.aoNoisy)));
  EXPECT_TRUE(Contains(dot, "label=\"transfer read\""));
}

TEST(GraphDot, GraphvizAcceptsPipelineAndEscapedNames) {
  if (!haveDot()) GTEST_SKIP() << "graphviz `dot` is not on PATH";
  for (const Readback rb : {Readback::Noisy, Readback::Temporal}) {
    Pipeline p = buildPipeline({.normalsImported = rb == Readback::Noisy, .readback = rb});
    std::string svg;
    const int rc = runDot(toDot(p.graph, p.graph.compile()), "aor_graph_pipeline", &svg);
    EXPECT_EQ(rc, 0);
    EXPECT_TRUE(Contains(svg, "<svg"));
    EXPECT_TRUE(Contains(svg, "gtao"));
  }
  // Names that need escaping in DOT.
  RenderGraph g;
  const ResourceId a = g.createImage("weird \"quoted\" \\ name {x} <y>;", {4, 4, VK_FORMAT_R8_UNORM});
  const ResourceId b = g.createImage("line\nbreak", {4, 4, VK_FORMAT_R8_UNORM});
  g.addPass("pass \"one\" -> [two]", [&](PassBuilder& pb) { pb.write(a); });
  g.addPass("dead \\ end", [&](PassBuilder& pb) { pb.read(a); pb.write(b); });
  g.addPass("graph } digraph {", [&](PassBuilder& pb) { pb.read(a, Access::TransferRead); pb.sideEffect(); });
  const CompiledGraph c = g.compile();
  checkCompiled(g, c);
  std::string svg;
  EXPECT_EQ(runDot(toDot(g, c), "aor_graph_escaped", &svg), 0) << toDot(g, c);
  EXPECT_TRUE(Contains(svg, "quoted"));
}

TEST(GraphDot, GraphvizAcceptsRandomGraphs) {
  if (!haveDot()) GTEST_SKIP() << "graphviz `dot` is not on PATH";
  for (uint32_t seed = 7; seed < 12; ++seed) {
    RandomGraph r = randomGraph(seed);
    EXPECT_EQ(runDot(toDot(r.graph, r.graph.compile()), "aor_graph_random"), 0) << "seed " << seed;
  }
}

}  // namespace
}  // namespace aor::graph::testing
