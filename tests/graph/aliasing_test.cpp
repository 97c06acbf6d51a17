// Memory aliasing of transients: slot assignment, sizes, and exhaustive non-overlap checks.
#include <string>

#include "graph_test_support.h"

namespace aor::graph::testing {
namespace {

bool shareSlot(const CompiledGraph& c, ResourceId a, ResourceId b) {
  return c.resources[a].memorySlot >= 0 && c.resources[a].memorySlot == c.resources[b].memorySlot;
}

TEST(GraphAliasing, PipelineReusesDeadNormalsForBlurredAo) {
  Pipeline p = buildPipeline();
  const CompiledGraph c = p.graph.compile();
  checkCompiled(p.graph, c);
  // normals_reconstructed dies at gtao; ao_blurred is born at spatial, after it.
  EXPECT_TRUE(shareSlot(c, p.normalsReconstructed, p.aoBlurred));
  EXPECT_FALSE(shareSlot(c, p.viewDepth, p.aoNoisy));
  EXPECT_FALSE(shareSlot(c, p.aoNoisy, p.aoBlurred));  // overlap at spatial
  EXPECT_FALSE(shareSlot(c, p.normalsReconstructed, p.aoNoisy));  // overlap at gtao
  EXPECT_EQ(c.slots.size(), 3u);
  EXPECT_LT(c.transientBytes, c.unaliasedTransientBytes);
  const auto bytes = [&](ResourceId id) { return imageBytes(p.graph.resources()[id].desc); };
  EXPECT_EQ(c.unaliasedTransientBytes,
            bytes(p.viewDepth) + bytes(p.normalsReconstructed) + bytes(p.aoNoisy) + bytes(p.aoBlurred));
  EXPECT_EQ(c.transientBytes, bytes(p.viewDepth) + bytes(p.normalsReconstructed) + bytes(p.aoNoisy));
  EXPECT_EQ(c.slots[c.resources[p.aoBlurred].memorySlot].resources,
            (std::vector<ResourceId>{p.normalsReconstructed, p.aoBlurred}));
}

TEST(GraphAliasing, AoNoisyReusesADeadPrefilterImage) {
  // A graph where ao_noisy must alias: depth_prefilter is dead once gtao starts.
  RenderGraph g;
  const ImageDesc d{640, 480, VK_FORMAT_R16_SFLOAT};
  const ResourceId raw = g.importImage("depth_raw", {640, 480, VK_FORMAT_R32_SFLOAT});
  const ResourceId prefilter = g.createImage("depth_prefilter", d);
  const ResourceId viewDepth = g.createImage("view_depth", {640, 480, VK_FORMAT_R32_SFLOAT});
  const ResourceId noisy = g.createImage("ao_noisy", {640, 480, VK_FORMAT_R8_UNORM});
  g.addPass("upload", [&](PassBuilder& b) { b.write(raw, Access::TransferWrite); });
  g.addPass("prefilter", [&](PassBuilder& b) { b.read(raw); b.write(prefilter); });
  g.addPass("linearize", [&](PassBuilder& b) { b.read(prefilter); b.write(viewDepth); });
  g.addPass("gtao", [&](PassBuilder& b) { b.read(viewDepth); b.write(noisy); });
  g.addPass("readback", [&](PassBuilder& b) { b.read(noisy, Access::TransferRead); b.sideEffect(); });
  const CompiledGraph c = g.compile();
  checkCompiled(g, c);
  EXPECT_TRUE(shareSlot(c, prefilter, noisy));
  EXPECT_FALSE(shareSlot(c, prefilter, viewDepth));
  EXPECT_EQ(c.transientBytes, imageBytes(d) + imageBytes(g.resources()[viewDepth].desc));
  EXPECT_LT(c.transientBytes, c.unaliasedTransientBytes);
}

TEST(GraphAliasing, HistoryAndImportedNeverGetSlots) {
  for (const bool valid : {true, false}) {
    Pipeline p = buildPipeline({.historyValid = valid});
    const CompiledGraph c = p.graph.compile();
    checkCompiled(p.graph, c);
    EXPECT_EQ(c.resources[p.depthRaw].memorySlot, -1);
    EXPECT_EQ(c.resources[p.history.current].memorySlot, -1);
    if (valid) {
      EXPECT_EQ(c.resources[p.history.previous].memorySlot, -1);
    }
    for (const MemorySlot& slot : c.slots) {
      for (ResourceId id : slot.resources) {
        EXPECT_EQ(p.graph.resources()[id].kind, ResourceKind::Transient);
      }
    }
  }
}

// Two transients A and B live in passes 0..1; C is born at pass 2 and may reuse either slot.
struct SlotChoice {
  VkFormat a, b, c;
  int expectedWith;  // 0: shares with A, 1: shares with B
};

class GraphSlotPreference : public ::testing::TestWithParam<SlotChoice> {};

TEST_P(GraphSlotPreference, PicksClosestFittingElseLargest) {
  const SlotChoice s = GetParam();
  RenderGraph g;
  const ResourceId a = g.createImage("A", {32, 32, s.a});
  const ResourceId b = g.createImage("B", {32, 32, s.b});
  const ResourceId c = g.createImage("C", {32, 32, s.c});
  g.addPass("make", [&](PassBuilder& p) { p.write(a); p.write(b); });
  g.addPass("use", [&](PassBuilder& p) { p.read(a); p.read(b); p.sideEffect(); });
  g.addPass("makeC", [&](PassBuilder& p) { p.write(c); });
  g.addPass("useC", [&](PassBuilder& p) { p.read(c); p.sideEffect(); });
  const CompiledGraph cg = g.compile();
  checkCompiled(g, cg);
  ASSERT_EQ(cg.slots.size(), 2u);
  EXPECT_TRUE(shareSlot(cg, c, s.expectedWith == 0 ? a : b));
  const uint64_t ba = imageBytes(g.resources()[a].desc), bb = imageBytes(g.resources()[b].desc),
                 bc = imageBytes(g.resources()[c].desc);
  const uint64_t grown = s.expectedWith == 0 ? std::max(ba, bc) + bb : ba + std::max(bb, bc);
  EXPECT_EQ(cg.transientBytes, grown);
}

INSTANTIATE_TEST_SUITE_P(
    Graph, GraphSlotPreference,
    ::testing::Values(
        // Both fit: the smaller one that fits.
        SlotChoice{VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_R32_SFLOAT, VK_FORMAT_R16_SFLOAT, 1},
        SlotChoice{VK_FORMAT_R32_SFLOAT, VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_R16_SFLOAT, 0},
        // Only one fits.
        SlotChoice{VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_R8_UNORM, VK_FORMAT_R32_SFLOAT, 0},
        SlotChoice{VK_FORMAT_R8_UNORM, VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_R32_SFLOAT, 1},
        // Neither fits: the larger one, so the slot grows least.
        SlotChoice{VK_FORMAT_R32_SFLOAT, VK_FORMAT_R8_UNORM, VK_FORMAT_R32G32B32A32_SFLOAT, 0},
        SlotChoice{VK_FORMAT_R8_UNORM, VK_FORMAT_R16_SFLOAT, VK_FORMAT_R32G32B32A32_SFLOAT, 1}));

TEST(GraphAliasing, OverlappingLifetimesNeverShare) {
  // Every transient is alive across the middle pass, so none may alias.
  RenderGraph g;
  std::vector<ResourceId> ids;
  for (int i = 0; i < 6; ++i) ids.push_back(g.createImage("t" + std::to_string(i), {16, 16, VK_FORMAT_R8_UNORM}));
  g.addPass("produce", [&](PassBuilder& b) { for (ResourceId id : ids) b.write(id); });
  g.addPass("consume", [&](PassBuilder& b) { for (ResourceId id : ids) b.read(id); b.sideEffect(); });
  const CompiledGraph c = g.compile();
  checkCompiled(g, c);
  EXPECT_EQ(c.slots.size(), ids.size());
  EXPECT_EQ(c.transientBytes, c.unaliasedTransientBytes);
}

TEST(GraphAliasing, SamePassBoundaryIsAnOverlap) {
  // A dies in pass 1 and B is born in pass 1: they are alive together and cannot alias.
  RenderGraph g;
  const ResourceId a = g.createImage("A", {16, 16, VK_FORMAT_R8_UNORM});
  const ResourceId b = g.createImage("B", {16, 16, VK_FORMAT_R8_UNORM});
  g.addPass("p0", [&](PassBuilder& p) { p.write(a); });
  g.addPass("p1", [&](PassBuilder& p) { p.read(a); p.write(b); });
  g.addPass("p2", [&](PassBuilder& p) { p.read(b); p.sideEffect(); });
  const CompiledGraph c = g.compile();
  checkCompiled(g, c);
  EXPECT_FALSE(shareSlot(c, a, b));
}

TEST(GraphAliasing, SeveralPipelineVariantsAreConsistent) {
  for (const bool normalsImported : {false, true}) {
    for (const bool historyValid : {false, true}) {
      for (const bool edgeWeights : {false, true}) {
        for (const Readback rb : {Readback::Noisy, Readback::Blurred, Readback::Temporal}) {
          SCOPED_TRACE(::testing::Message() << "normalsImported=" << normalsImported
                                            << " historyValid=" << historyValid
                                            << " edgeWeights=" << edgeWeights
                                            << " readback=" << static_cast<int>(rb));
          Pipeline p = buildPipeline({.normalsImported = normalsImported,
                                      .historyValid = historyValid,
                                      .edgeWeights = edgeWeights,
                                      .readback = rb});
          checkCompiled(p.graph, p.graph.compile());
        }
      }
    }
  }
}

TEST(GraphAliasing, RandomGraphsNeverOverlapInASlot) {
  size_t sharedSlots = 0, culled = 0, graphsWithSavings = 0;
  for (uint32_t seed = 1; seed <= 200; ++seed) {
    SCOPED_TRACE(::testing::Message() << "random graph seed " << seed);
    RandomGraph r = randomGraph(seed);
    const CompiledGraph c = r.graph.compile();
    for (const MemorySlot& slot : c.slots) {
      sharedSlots += slot.resources.size() > 1;
      for (size_t i = 0; i < slot.resources.size(); ++i) {
        for (size_t j = i + 1; j < slot.resources.size(); ++j) {
          const CompiledResource& a = c.resources[slot.resources[i]];
          const CompiledResource& b = c.resources[slot.resources[j]];
          ASSERT_TRUE(a.lastPass < b.firstPass || b.lastPass < a.firstPass);
        }
      }
    }
    culled += c.culled.size();
    graphsWithSavings += c.transientBytes < c.unaliasedTransientBytes;
    checkCompiled(r.graph, c);
    if (HasFatalFailure()) return;
  }
  // The generator must actually exercise aliasing and culling, or this test proves nothing.
  EXPECT_GT(sharedSlots, 50u);
  EXPECT_GT(graphsWithSavings, 20u);
  EXPECT_GT(culled, 50u);
}

}  // namespace
}  // namespace aor::graph::testing
