// Culling, lifetimes, usage flags and error handling of the render graph.
#include <stdexcept>
#include <string>

#include "graph_test_support.h"

namespace aor::graph::testing {
namespace {

::testing::AssertionResult Contains(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "'" << text << "' does not contain '" << part << "'";
}

TEST(GraphCulling, FullPipelineRunsEveryPass) {
  Pipeline p = buildPipeline();
  const CompiledGraph c = p.graph.compile();
  checkCompiled(p.graph, c);
  EXPECT_TRUE(c.culled.empty());
  ASSERT_EQ(c.passes.size(), p.graph.passes().size());
  for (size_t i = 0; i < c.passes.size(); ++i) EXPECT_EQ(c.passes[i].pass, i);
}

TEST(GraphCulling, ReadbackOfNoisyAoCullsSpatialAndTemporal) {
  Pipeline p = buildPipeline({.readback = Readback::Noisy});
  const CompiledGraph c = p.graph.compile();
  checkCompiled(p.graph, c);
  ASSERT_TRUE(isCulled(c, p.spatial));
  ASSERT_TRUE(isCulled(c, p.temporal));
  EXPECT_FALSE(isCulled(c, p.gtao));
  EXPECT_FALSE(isCulled(c, p.linearize));
  EXPECT_FALSE(isCulled(c, p.upload));
  EXPECT_FALSE(isCulled(c, p.readback));
  EXPECT_EQ(c.culled.size(), 2u);
  // Reasons name the outputs nobody live consumes.
  EXPECT_TRUE(Contains(culledReason(c, p.spatial), "writes ao_blurred, which no live pass reads"));
  EXPECT_TRUE(Contains(culledReason(c, p.spatial), "temporal"))  // its only reader was culled
      << culledReason(c, p.spatial);
  EXPECT_TRUE(Contains(culledReason(c, p.temporal),
                       "writes ao_history.current, which no live pass reads"));
}

TEST(GraphCulling, ImportedNormalsCullReconstruction) {
  Pipeline p = buildPipeline({.normalsImported = true});
  const CompiledGraph c = p.graph.compile();
  checkCompiled(p.graph, c);
  ASSERT_TRUE(isCulled(c, p.reconstructNormals));
  EXPECT_EQ(c.culled.size(), 1u);
  EXPECT_TRUE(Contains(culledReason(c, p.reconstructNormals),
                       "writes normals_reconstructed, which no live pass reads"));
  EXPECT_FALSE(c.resources[p.normalsReconstructed].used);
  EXPECT_EQ(c.resources[p.normalsReconstructed].memorySlot, -1);
  EXPECT_TRUE(c.resources[p.normalsImported].used);
  EXPECT_EQ(c.resources[p.normalsImported].usage, VkImageUsageFlags(VK_IMAGE_USAGE_SAMPLED_BIT));
}

TEST(GraphCulling, IsTransitive) {
  // edge_weights is consumed only by spatial; once spatial is dead, so is its producer.
  Pipeline p = buildPipeline({.edgeWeights = true, .readback = Readback::Noisy});
  const CompiledGraph c = p.graph.compile();
  checkCompiled(p.graph, c);
  EXPECT_TRUE(isCulled(c, p.edgeWeightsPass));
  EXPECT_TRUE(isCulled(c, p.spatial));
  EXPECT_TRUE(isCulled(c, p.temporal));
  EXPECT_TRUE(Contains(culledReason(c, p.edgeWeightsPass), "edge_weights"));
  EXPECT_TRUE(Contains(culledReason(c, p.edgeWeightsPass), "spatial"));
  EXPECT_FALSE(c.resources[p.edgeWeights].used);

  // With the full pipeline the same pass is live.
  Pipeline full = buildPipeline({.edgeWeights = true});
  const CompiledGraph cf = full.graph.compile();
  checkCompiled(full.graph, cf);
  EXPECT_FALSE(isCulled(cf, full.edgeWeightsPass));
}

TEST(GraphCulling, LongChainDiesFromTheEnd) {
  RenderGraph g;
  const ImageDesc d{8, 8, VK_FORMAT_R16_SFLOAT};
  std::vector<ResourceId> img;
  for (int i = 0; i < 5; ++i) img.push_back(g.createImage("c" + std::to_string(i), d));
  g.addPass("p0", [&](PassBuilder& b) { b.write(img[0]); });
  for (int i = 1; i < 5; ++i) {
    g.addPass("p" + std::to_string(i), [&](PassBuilder& b) {
      b.read(img[i - 1]);
      b.write(img[i]);
    });
  }
  g.addPass("sink", [&](PassBuilder& b) { b.read(img[2]); b.sideEffect(); });
  const CompiledGraph c = g.compile();
  checkCompiled(g, c);
  EXPECT_EQ(c.passes.size(), 4u);  // p0, p1, p2, sink
  EXPECT_TRUE(isCulled(c, 3));
  EXPECT_TRUE(isCulled(c, 4));
  EXPECT_TRUE(Contains(culledReason(c, 3), "writes c3"));
  EXPECT_TRUE(Contains(culledReason(c, 4), "writes c4"));
}

TEST(GraphCulling, PassWithoutOutputsOrSideEffects) {
  RenderGraph g;
  const ResourceId in = g.importImage("in", {4, 4, VK_FORMAT_R8_UNORM});
  g.addPass("looker", [&](PassBuilder& b) { b.read(in); });
  g.addPass("empty", {});
  g.addPass("root", [&](PassBuilder& b) { b.sideEffect(); });
  const CompiledGraph c = g.compile();
  checkCompiled(g, c);
  EXPECT_EQ(culledReason(c, 0), "no outputs and no side effects");
  EXPECT_EQ(culledReason(c, 1), "no outputs and no side effects");
  ASSERT_EQ(c.passes.size(), 1u);
  EXPECT_EQ(c.passes[0].pass, 2u);
  EXPECT_FALSE(c.resources[in].used);
  EXPECT_EQ(c.persistentBytes, 0u);
}

TEST(GraphCulling, OverwrittenOutputIsDead) {
  // Two passes write the same image before anyone reads it: only the second one matters.
  RenderGraph g;
  const ResourceId t = g.createImage("t", {4, 4, VK_FORMAT_R8_UNORM});
  g.addPass("first", [&](PassBuilder& b) { b.write(t); });
  g.addPass("second", [&](PassBuilder& b) { b.write(t); });
  g.addPass("sink", [&](PassBuilder& b) { b.read(t); b.sideEffect(); });
  const CompiledGraph c = g.compile();
  checkCompiled(g, c);
  EXPECT_TRUE(isCulled(c, 0));
  EXPECT_FALSE(isCulled(c, 1));
  EXPECT_TRUE(Contains(culledReason(c, 0), "writes t, which no live pass reads"));
}

TEST(GraphCulling, ReadModifyWriteChainKeepsEveryStep) {
  RenderGraph g;
  const ResourceId t = g.createImage("accum", {4, 4, VK_FORMAT_R32_SFLOAT});
  g.addPass("clear", [&](PassBuilder& b) { b.write(t, Access::TransferWrite); });
  g.addPass("add1", [&](PassBuilder& b) { b.read(t, Access::StorageRead); b.write(t); });
  g.addPass("add2", [&](PassBuilder& b) { b.read(t, Access::StorageRead); b.write(t); });
  g.addPass("sink", [&](PassBuilder& b) { b.read(t, Access::TransferRead); b.sideEffect(); });
  const CompiledGraph c = g.compile();
  checkCompiled(g, c);
  EXPECT_TRUE(c.culled.empty());
  EXPECT_EQ(c.resources[t].usage, VkImageUsageFlags(VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                                                    VK_IMAGE_USAGE_STORAGE_BIT |
                                                    VK_IMAGE_USAGE_TRANSFER_SRC_BIT));
}

TEST(GraphHistory, NoMemoryWhenTemporalIsCulled) {
  Pipeline p = buildPipeline({.readback = Readback::Noisy});
  const CompiledGraph c = p.graph.compile();
  checkCompiled(p.graph, c);
  ASSERT_NE(p.history.previous, kNoResource);
  EXPECT_FALSE(c.resources[p.history.previous].used);
  EXPECT_FALSE(c.resources[p.history.current].used);
  EXPECT_EQ(c.resources[p.history.previous].memorySlot, -1);
  EXPECT_EQ(barrierCount(c, p.history.previous), 0u);
  EXPECT_EQ(barrierCount(c, p.history.current), 0u);
  // Only depth_raw is persistent.
  EXPECT_EQ(c.persistentBytes, imageBytes(p.graph.resources()[p.depthRaw].desc));

  Pipeline full = buildPipeline();
  const CompiledGraph cf = full.graph.compile();
  const uint64_t history = imageBytes(full.graph.resources()[full.history.current].desc);
  EXPECT_EQ(cf.persistentBytes,
            imageBytes(full.graph.resources()[full.depthRaw].desc) + 2 * history);
}

TEST(GraphHistory, NamesAndValidity) {
  RenderGraph g;
  const ImageDesc d{16, 16, VK_FORMAT_R16G16_SFLOAT};
  const ResourceState prev{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                        VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_IMAGE_LAYOUT_GENERAL};
  const HistoryPair valid = g.createHistory("ao", d, true, prev);
  const HistoryPair invalid = g.createHistory("other", d, false);
  ASSERT_NE(valid.previous, kNoResource);
  EXPECT_EQ(g.resources()[valid.previous].name, "ao.previous");
  EXPECT_EQ(g.resources()[valid.current].name, "ao.current");
  EXPECT_EQ(g.resources()[valid.previous].kind, ResourceKind::History);
  EXPECT_EQ(g.resources()[valid.current].kind, ResourceKind::History);
  EXPECT_TRUE(sameState(g.resources()[valid.previous].initialState, prev));
  EXPECT_EQ(invalid.previous, kNoResource);
  EXPECT_EQ(g.resources()[invalid.current].name, "other.current");
  EXPECT_EQ(g.resources().size(), 3u);
}

TEST(GraphHistory, InvalidHistoryPipelineCompiles) {
  Pipeline p = buildPipeline({.historyValid = false});
  const CompiledGraph c = p.graph.compile();
  checkCompiled(p.graph, c);
  EXPECT_EQ(p.history.previous, kNoResource);
  EXPECT_TRUE(c.resources[p.history.current].used);
  EXPECT_TRUE(c.culled.empty());
}

TEST(GraphLifetimes, FirstLastAndUsageUnions) {
  Pipeline p = buildPipeline();
  const CompiledGraph c = p.graph.compile();
  checkCompiled(p.graph, c);
  const auto idx = [&](uint32_t pass) { return compiledIndex(c, pass); };
  const auto& r = c.resources;
  EXPECT_EQ(r[p.depthRaw].firstPass, idx(p.upload));
  EXPECT_EQ(r[p.depthRaw].lastPass, idx(p.linearize));
  EXPECT_EQ(r[p.viewDepth].firstPass, idx(p.linearize));
  EXPECT_EQ(r[p.viewDepth].lastPass, idx(p.temporal));
  EXPECT_EQ(r[p.normalsReconstructed].firstPass, idx(p.reconstructNormals));
  EXPECT_EQ(r[p.normalsReconstructed].lastPass, idx(p.gtao));
  EXPECT_EQ(r[p.aoNoisy].firstPass, idx(p.gtao));
  EXPECT_EQ(r[p.aoNoisy].lastPass, idx(p.spatial));
  EXPECT_EQ(r[p.aoBlurred].firstPass, idx(p.spatial));
  EXPECT_EQ(r[p.aoBlurred].lastPass, idx(p.temporal));
  EXPECT_EQ(r[p.history.previous].firstPass, idx(p.temporal));
  EXPECT_EQ(r[p.history.previous].lastPass, idx(p.temporal));
  EXPECT_EQ(r[p.history.current].firstPass, idx(p.temporal));
  EXPECT_EQ(r[p.history.current].lastPass, idx(p.readback));

  EXPECT_EQ(r[p.depthRaw].usage,
            VkImageUsageFlags(VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT));
  EXPECT_EQ(r[p.viewDepth].usage,
            VkImageUsageFlags(VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT));
  EXPECT_EQ(r[p.history.current].usage,
            VkImageUsageFlags(VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT));
  EXPECT_EQ(r[p.history.previous].usage, VkImageUsageFlags(VK_IMAGE_USAGE_SAMPLED_BIT));
}

TEST(GraphLifetimes, IndicesAreIntoCompiledPassesAndIgnoreCulledAccesses) {
  // reconstruct_normals is culled, so view_depth's lifetime starts at linearize and its usage
  // still includes SAMPLED only through live readers.
  Pipeline p = buildPipeline({.normalsImported = true, .readback = Readback::Noisy});
  const CompiledGraph c = p.graph.compile();
  checkCompiled(p.graph, c);
  ASSERT_EQ(c.passes.size(), 4u);  // upload, linearize, gtao, readback
  EXPECT_EQ(c.resources[p.aoNoisy].firstPass, 2);
  EXPECT_EQ(c.resources[p.aoNoisy].lastPass, 3);
  EXPECT_EQ(c.resources[p.aoNoisy].usage,
            VkImageUsageFlags(VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT));
  EXPECT_EQ(c.resources[p.viewDepth].lastPass, 2);  // spatial/temporal reads are culled
}

// ---------------------------------------------------------------------------------------------
// Errors

TEST(GraphErrors, ReadingNoResourceThrowsNamingThePass) {
  RenderGraph g;
  const HistoryPair h = g.createHistory("ao_history", {8, 8, VK_FORMAT_R16_SFLOAT}, false);
  try {
    g.addPass("temporal", [&](PassBuilder& b) { b.read(h.previous); });
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_TRUE(Contains(e.what(), "temporal"));
  }
  EXPECT_TRUE(g.passes().empty()) << "a failed addPass must not leave a half-declared pass";
}

TEST(GraphErrors, OutOfRangeIdsThrow) {
  RenderGraph g;
  const ResourceId t = g.createImage("t", {8, 8, VK_FORMAT_R8_UNORM});
  EXPECT_THROW(g.addPass("bad_read", [&](PassBuilder& b) { b.read(t + 1); }),
               std::invalid_argument);
  EXPECT_THROW(g.addPass("bad_write", [&](PassBuilder& b) { b.write(kNoResource); }),
               std::invalid_argument);
  EXPECT_THROW(g.addPass("bad_write2", [&](PassBuilder& b) { b.write(42); }),
               std::invalid_argument);
  try {
    g.addPass("bad_read_named", [&](PassBuilder& b) { b.read(7); });
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_TRUE(Contains(e.what(), "bad_read_named"));
  }
  EXPECT_TRUE(g.passes().empty());
}

TEST(GraphErrors, AccessDirectionMustMatch) {
  RenderGraph g;
  const ResourceId t = g.createImage("t", {8, 8, VK_FORMAT_R8_UNORM});
  EXPECT_THROW(g.addPass("p", [&](PassBuilder& b) { b.read(t, Access::StorageWrite); }),
               std::invalid_argument);
  EXPECT_THROW(g.addPass("p", [&](PassBuilder& b) { b.write(t, Access::SampledRead); }),
               std::invalid_argument);
}

TEST(GraphErrors, InvalidImageDescriptionsThrow) {
  RenderGraph g;
  EXPECT_THROW(g.createImage("zero", {0, 8, VK_FORMAT_R8_UNORM}), std::invalid_argument);
  EXPECT_THROW(g.importImage("nofmt", {8, 8, VK_FORMAT_UNDEFINED}), std::invalid_argument);
  EXPECT_THROW(g.createHistory("bc", {8, 8, VK_FORMAT_BC1_RGB_UNORM_BLOCK}, true),
               std::invalid_argument);
  EXPECT_TRUE(g.resources().empty());
}

TEST(GraphErrors, ReadingUnwrittenTransientThrowsInCompile) {
  RenderGraph g;
  const ResourceId never = g.createImage("ao_noisy", {8, 8, VK_FORMAT_R8_UNORM});
  const ResourceId out = g.createImage("ao_blurred", {8, 8, VK_FORMAT_R8_UNORM});
  g.addPass("spatial", [&](PassBuilder& b) {
    b.read(never);
    b.write(out);
  });
  g.addPass("readback", [&](PassBuilder& b) { b.read(out, Access::TransferRead); b.sideEffect(); });
  try {
    (void)g.compile();
    FAIL() << "expected std::logic_error";
  } catch (const std::logic_error& e) {
    EXPECT_TRUE(Contains(e.what(), "spatial"));
    EXPECT_TRUE(Contains(e.what(), "ao_noisy"));
  }
}

TEST(GraphErrors, ReadingBeforeALaterWriterThrows) {
  // Declaration order is execution order: a writer declared after the reader does not count.
  RenderGraph g;
  const ResourceId t = g.createImage("view_depth", {8, 8, VK_FORMAT_R32_SFLOAT});
  g.addPass("gtao", [&](PassBuilder& b) { b.read(t); b.sideEffect(); });
  g.addPass("linearize", [&](PassBuilder& b) { b.write(t); });
  EXPECT_THROW((void)g.compile(), std::logic_error);
}

TEST(GraphErrors, ReadModifyWriteWithoutEarlierWriterThrows) {
  RenderGraph g;
  const ResourceId t = g.createImage("accum", {8, 8, VK_FORMAT_R32_SFLOAT});
  g.addPass("accumulate", [&](PassBuilder& b) {
    b.read(t, Access::StorageRead);
    b.write(t);
    b.sideEffect();
  });
  EXPECT_THROW((void)g.compile(), std::logic_error);
}

TEST(GraphErrors, ReadingUnwrittenHistoryCurrentThrowsEvenInCulledPass) {
  RenderGraph g;
  const HistoryPair h = g.createHistory("ao_history", {8, 8, VK_FORMAT_R16_SFLOAT}, true);
  g.addPass("peek", [&](PassBuilder& b) { b.read(h.current); });  // would be culled
  g.addPass("root", [&](PassBuilder& b) { b.read(h.previous); b.sideEffect(); });
  try {
    (void)g.compile();
    FAIL();
  } catch (const std::logic_error& e) {
    EXPECT_TRUE(Contains(e.what(), "peek"));
    EXPECT_TRUE(Contains(e.what(), "ao_history.current"));
  }
}

TEST(GraphErrors, ImportedAndHistoryPreviousMayBeReadWithoutWriter) {
  RenderGraph g;
  const ResourceId in = g.importImage("normals", {8, 8, VK_FORMAT_A2B10G10R10_UNORM_PACK32});
  const HistoryPair h = g.createHistory("ao_history", {8, 8, VK_FORMAT_R16_SFLOAT}, true);
  g.addPass("root", [&](PassBuilder& b) {
    b.read(in);
    b.read(h.previous);
    b.sideEffect();
  });
  const CompiledGraph c = g.compile();
  checkCompiled(g, c);
  EXPECT_FALSE(c.resources[h.current].used);
}

}  // namespace
}  // namespace aor::graph::testing
