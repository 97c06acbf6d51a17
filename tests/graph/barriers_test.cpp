// Barrier derivation: exact barriers for small graphs, and the synchronisation checker applied to
// the pipeline, multi-frame history hand-over and random graphs.
#include <gtest/gtest-spi.h>

#include <string>

#include "graph_test_support.h"

namespace aor::graph::testing {
namespace {

constexpr ResourceState kSampled{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                              VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
                              VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
constexpr ResourceState kStorageRead{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                  VK_ACCESS_2_SHADER_STORAGE_READ_BIT, VK_IMAGE_LAYOUT_GENERAL};
constexpr ResourceState kStorageWrite{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                   VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_IMAGE_LAYOUT_GENERAL};
constexpr ResourceState kTransferRead{VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                                   VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL};
constexpr ResourceState kTransferWrite{VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                    VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL};
constexpr ResourceState kClearWrite{VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL};
constexpr ResourceState kFresh{};

#define EXPECT_STATE(actual, expected)                                              \
  EXPECT_TRUE(sameState(actual, expected)) << "got " << stateText(actual) << "\n" \
                                           << "expected " << stateText(expected)

TEST(GraphRequiredState, MatchesTheAccessTable) {
  EXPECT_STATE(requiredState(Access::SampledRead), kSampled);
  EXPECT_STATE(requiredState(Access::StorageRead), kStorageRead);
  EXPECT_STATE(requiredState(Access::StorageWrite), kStorageWrite);
  EXPECT_STATE(requiredState(Access::TransferRead), kTransferRead);
  EXPECT_STATE(requiredState(Access::TransferWrite), kTransferWrite);
  EXPECT_STATE(requiredState(Access::ClearWrite), kClearWrite);
  EXPECT_FALSE(isWrite(Access::SampledRead));
  EXPECT_FALSE(isWrite(Access::StorageRead));
  EXPECT_FALSE(isWrite(Access::TransferRead));
  EXPECT_TRUE(isWrite(Access::StorageWrite));
  EXPECT_TRUE(isWrite(Access::TransferWrite));
  EXPECT_TRUE(isWrite(Access::ClearWrite));
}

TEST(GraphBarriers, PipelineBarriersAreExactlyTheNeededOnes) {
  Pipeline p = buildPipeline();
  const CompiledGraph c = p.graph.compile();
  checkCompiled(p.graph, c);

  // upload: depth_raw UNDEFINED -> TRANSFER_DST (imported, nothing before).
  auto b = barriersOn(c, p.upload, p.depthRaw);
  ASSERT_EQ(b.size(), 1u);
  EXPECT_STATE(b[0].before, kFresh);
  EXPECT_STATE(b[0].after, kTransferWrite);
  // linearize: RAW on depth_raw (copy write -> sampled read), first use of view_depth.
  b = barriersOn(c, p.linearize, p.depthRaw);
  ASSERT_EQ(b.size(), 1u);
  EXPECT_STATE(b[0].before, kTransferWrite);
  EXPECT_STATE(b[0].after, kSampled);
  b = barriersOn(c, p.linearize, p.viewDepth);
  ASSERT_EQ(b.size(), 1u);
  EXPECT_STATE(b[0].before, kFresh);
  EXPECT_STATE(b[0].after, kStorageWrite);
  // view_depth: one RAW barrier before its first reader; later readers share the layout.
  b = barriersOn(c, p.reconstructNormals, p.viewDepth);
  ASSERT_EQ(b.size(), 1u);
  EXPECT_STATE(b[0].before, kStorageWrite);
  EXPECT_STATE(b[0].after, kSampled);
  EXPECT_TRUE(barriersOn(c, p.gtao, p.viewDepth).empty());
  EXPECT_TRUE(barriersOn(c, p.spatial, p.viewDepth).empty());
  EXPECT_TRUE(barriersOn(c, p.temporal, p.viewDepth).empty());
  EXPECT_EQ(barrierCount(c, p.viewDepth), 2u);
  // ao_blurred reuses normals_reconstructed's memory: its first barrier waits for gtao's read.
  b = barriersOn(c, p.spatial, p.aoBlurred);
  ASSERT_EQ(b.size(), 1u);
  EXPECT_STATE(b[0].before, (ResourceState{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                        VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
                                        VK_IMAGE_LAYOUT_UNDEFINED}));
  EXPECT_STATE(b[0].after, kStorageWrite);
  // history previous starts from the state the caller gave (last frame's read-back).
  b = barriersOn(c, p.temporal, p.history.previous);
  ASSERT_EQ(b.size(), 1u);
  EXPECT_STATE(b[0].before, kTransferRead);
  EXPECT_STATE(b[0].after, kSampled);
  // readback: RAW on the history image.
  b = barriersOn(c, p.readback, p.history.current);
  ASSERT_EQ(b.size(), 1u);
  EXPECT_STATE(b[0].before, kStorageWrite);
  EXPECT_STATE(b[0].after, kTransferRead);

  // Final states the executor carries into the next frame.
  EXPECT_STATE(c.resources[p.history.current].finalState, kTransferRead);
  EXPECT_STATE(c.resources[p.history.previous].finalState, kSampled);
  EXPECT_STATE(c.resources[p.depthRaw].finalState, kSampled);
  EXPECT_STATE(c.resources[p.viewDepth].finalState, kSampled);
}

TEST(GraphBarriers, HistoryPreviousInitialStateDecidesTheFirstBarrier) {
  // Already in the layout and last only read: nothing to do.
  {
    Pipeline p = buildPipeline({.historyPreviousState = kSampled});
    const CompiledGraph c = p.graph.compile();
    checkCompiled(p.graph, c);
    EXPECT_EQ(barrierCount(c, p.history.previous), 0u);
    EXPECT_STATE(c.resources[p.history.previous].finalState, kSampled);
  }
  // Left written by a storage write in GENERAL: RAW + layout change from exactly that state.
  {
    Pipeline p = buildPipeline({.historyPreviousState = kStorageWrite});
    const CompiledGraph c = p.graph.compile();
    checkCompiled(p.graph, c);
    const auto b = barriersOn(c, p.temporal, p.history.previous);
    ASSERT_EQ(b.size(), 1u);
    EXPECT_STATE(b[0].before, kStorageWrite);
    EXPECT_STATE(b[0].after, kSampled);
  }
  // Already SHADER_READ_ONLY but the last write is still pending: barrier without layout change.
  {
    const ResourceState pending{VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                             VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    Pipeline p = buildPipeline({.historyPreviousState = pending});
    const CompiledGraph c = p.graph.compile();
    checkCompiled(p.graph, c);
    const auto b = barriersOn(c, p.temporal, p.history.previous);
    ASSERT_EQ(b.size(), 1u);
    EXPECT_STATE(b[0].before, pending);
    EXPECT_STATE(b[0].after, kSampled);
  }
}

TEST(GraphBarriers, HistoryHandOverAcrossFrames) {
  // Two physical images swap roles every frame; each frame's initial states are the final states
  // of the image in the previous frame. Every frame must pass the checker.
  ResourceState image[2] = {kFresh, kFresh};
  int currentImage = 0;
  bool valid = false;
  for (int frame = 0; frame < 4; ++frame) {
    SCOPED_TRACE(::testing::Message() << "frame " << frame);
    const int previousImage = 1 - currentImage;
    Pipeline p = buildPipeline({.historyValid = valid,
                                .historyPreviousState = image[previousImage],
                                .historyCurrentState = image[currentImage]});
    const CompiledGraph c = p.graph.compile();
    checkCompiled(p.graph, c);
    const auto b = barriersOn(c, p.temporal, p.history.current);
    ASSERT_EQ(b.size(), 1u);
    EXPECT_STATE(b[0].before, image[currentImage]);  // WAR against the old contents' last use
    if (valid) image[previousImage] = c.resources[p.history.previous].finalState;
    image[currentImage] = c.resources[p.history.current].finalState;
    EXPECT_STATE(image[currentImage], kTransferRead);
    currentImage = previousImage;
    valid = true;
  }
  // After the loop `currentImage` is the last frame's previous image (only sampled by temporal).
  EXPECT_STATE(image[currentImage], kSampled);
  EXPECT_STATE(image[1 - currentImage], kTransferRead);
}

TEST(GraphBarriers, ReadModifyWriteInOnePassNeedsOneBarrier) {
  RenderGraph g;
  const ResourceId t = g.createImage("accum", {8, 8, VK_FORMAT_R32_SFLOAT});
  g.addPass("init", [&](PassBuilder& b) { b.write(t); });
  g.addPass("accumulate", [&](PassBuilder& b) {
    b.read(t, Access::StorageRead);
    b.write(t, Access::StorageWrite);
  });
  g.addPass("readback", [&](PassBuilder& b) { b.read(t, Access::TransferRead); b.sideEffect(); });
  const CompiledGraph c = g.compile();
  checkCompiled(g, c);
  const auto b = barriersOn(c, 1, t);
  ASSERT_EQ(b.size(), 1u);
  EXPECT_STATE(b[0].before, kStorageWrite);
  EXPECT_STATE(b[0].after, (ResourceState{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                       VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
                                           VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                                       VK_IMAGE_LAYOUT_GENERAL}));
  const auto r = barriersOn(c, 2, t);
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].before.access,
            VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}

TEST(GraphBarriers, MixedLayoutsInOnePassUseGeneral) {
  RenderGraph g;
  const ResourceId t = g.createImage("img", {8, 8, VK_FORMAT_R16_SFLOAT});
  g.addPass("init", [&](PassBuilder& b) { b.write(t); });
  g.addPass("inplace", [&](PassBuilder& b) {
    b.read(t, Access::SampledRead);
    b.write(t, Access::StorageWrite);
  });
  g.addPass("sink", [&](PassBuilder& b) { b.read(t); b.sideEffect(); });
  const CompiledGraph c = g.compile();
  checkCompiled(g, c);
  const ResourceState need = requiredState(g.passes()[1], t);
  EXPECT_EQ(need.layout, VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_EQ(need.access, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  const auto b = barriersOn(c, 1, t);
  ASSERT_EQ(b.size(), 1u);
  EXPECT_STATE(b[0].after, need);
}

TEST(GraphBarriers, WarAfterSeveralReadersCoversAllOfThem) {
  RenderGraph g;
  const ResourceId t = g.createImage("img", {8, 8, VK_FORMAT_R16_SFLOAT});
  const ResourceId o1 = g.importImage("out1", {8, 8, VK_FORMAT_R16_SFLOAT});
  const ResourceId o2 = g.importImage("out2", {8, 8, VK_FORMAT_R16_SFLOAT});
  g.addPass("write", [&](PassBuilder& b) { b.write(t); });
  g.addPass("read1", [&](PassBuilder& b) { b.read(t, Access::StorageRead); b.write(o1); b.sideEffect(); });
  g.addPass("read2", [&](PassBuilder& b) { b.read(t, Access::StorageRead); b.write(o2); b.sideEffect(); });
  g.addPass("overwrite", [&](PassBuilder& b) { b.write(t, Access::TransferWrite); });
  g.addPass("sink", [&](PassBuilder& b) { b.read(t, Access::TransferRead); b.sideEffect(); });
  const CompiledGraph c = g.compile();
  checkCompiled(g, c);
  EXPECT_EQ(barriersOn(c, 1, t).size(), 1u);
  EXPECT_TRUE(barriersOn(c, 2, t).empty()) << "read after read in GENERAL";
  const auto b = barriersOn(c, 3, t);
  ASSERT_EQ(b.size(), 1u);
  EXPECT_STATE(b[0].before, kStorageRead);  // both readers (same stage/access here)
  EXPECT_STATE(b[0].after, kTransferWrite);
}

TEST(GraphBarriers, WarAfterReadersInDifferentStagesAccumulates) {
  // Two readers in the same layout but different stages: with only SampledRead/StorageRead/
  // TransferRead each layout has one stage, so build it through an imported image whose initial
  // state already has a reader (COPY) in GENERAL, then a compute storage read, then a write.
  RenderGraph g;
  const ResourceState copyRead{VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                            VK_IMAGE_LAYOUT_GENERAL};
  const ResourceId t = g.importImage("img", {8, 8, VK_FORMAT_R16_SFLOAT}, copyRead);
  const ResourceId o = g.importImage("out", {8, 8, VK_FORMAT_R16_SFLOAT});
  g.addPass("read", [&](PassBuilder& b) { b.read(t, Access::StorageRead); b.write(o); b.sideEffect(); });
  g.addPass("write", [&](PassBuilder& b) { b.write(t); b.sideEffect(); });
  const CompiledGraph c = g.compile();
  checkCompiled(g, c);
  EXPECT_TRUE(barriersOn(c, 0, t).empty()) << "read after read in GENERAL";
  const auto b = barriersOn(c, 1, t);
  ASSERT_EQ(b.size(), 1u);
  EXPECT_EQ(b[0].before.stage, VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
  EXPECT_EQ(b[0].before.access, VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  EXPECT_STATE(c.resources[t].finalState, kStorageWrite);
}

TEST(GraphBarriers, LayoutChangeBetweenReadsIsEmittedWithReaderAsSource) {
  RenderGraph g;
  const ResourceId t = g.createImage("img", {8, 8, VK_FORMAT_R8_UNORM});
  g.addPass("write", [&](PassBuilder& b) { b.write(t); });
  g.addPass("sample", [&](PassBuilder& b) { b.read(t); b.sideEffect(); });
  g.addPass("copy", [&](PassBuilder& b) { b.read(t, Access::TransferRead); b.sideEffect(); });
  g.addPass("sample2", [&](PassBuilder& b) { b.read(t); b.sideEffect(); });
  const CompiledGraph c = g.compile();
  checkCompiled(g, c);
  auto b = barriersOn(c, 2, t);
  ASSERT_EQ(b.size(), 1u);
  EXPECT_STATE(b[0].before, kSampled);
  EXPECT_STATE(b[0].after, kTransferRead);
  b = barriersOn(c, 3, t);
  ASSERT_EQ(b.size(), 1u);
  EXPECT_STATE(b[0].before, kTransferRead);
  EXPECT_STATE(b[0].after, kSampled);
}

TEST(GraphBarriers, WriteAfterWriteIsOrdered) {
  RenderGraph g;
  const ResourceId t = g.importImage("target", {8, 8, VK_FORMAT_R8_UNORM},
                                     {VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, VK_IMAGE_LAYOUT_GENERAL});
  g.addPass("a", [&](PassBuilder& b) { b.write(t); b.sideEffect(); });
  g.addPass("b", [&](PassBuilder& b) { b.write(t); b.sideEffect(); });
  const CompiledGraph c = g.compile();
  checkCompiled(g, c);
  EXPECT_TRUE(barriersOn(c, 0, t).empty()) << "GENERAL with no earlier access needs nothing";
  const auto b = barriersOn(c, 1, t);
  ASSERT_EQ(b.size(), 1u);
  EXPECT_STATE(b[0].before, kStorageWrite);
  EXPECT_STATE(b[0].after, kStorageWrite);
}

TEST(GraphBarriers, AliasedTransientWaitsForPreviousMemberWrite) {
  // The previous member's last access is a write nobody reads (its pass is live for another
  // output): the next member's first barrier must still wait for it.
  RenderGraph g;
  const ResourceId scratch = g.createImage("scratch", {8, 8, VK_FORMAT_R8_UNORM});
  const ResourceId keep = g.importImage("keep", {8, 8, VK_FORMAT_R8_UNORM});
  const ResourceId next = g.createImage("next", {8, 8, VK_FORMAT_R8_UNORM});
  g.addPass("a", [&](PassBuilder& b) { b.write(scratch, Access::TransferWrite); b.write(keep); b.sideEffect(); });
  g.addPass("b", [&](PassBuilder& b) { b.write(next); });
  g.addPass("c", [&](PassBuilder& b) { b.read(next); b.sideEffect(); });
  const CompiledGraph c = g.compile();
  checkCompiled(g, c);
  ASSERT_EQ(c.resources[scratch].memorySlot, c.resources[next].memorySlot);
  const auto b = barriersOn(c, 1, next);
  ASSERT_EQ(b.size(), 1u);
  EXPECT_STATE(b[0].before, (ResourceState{VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                        VK_IMAGE_LAYOUT_UNDEFINED}));
}

TEST(GraphBarriers, CheckerRejectsBrokenBarriers) {
  // The checker itself must be able to fail: corrupt a correct compilation in several ways.
  Pipeline p = buildPipeline();
  const CompiledGraph good = p.graph.compile();
  const int spatial = compiledIndex(good, p.spatial);
  const int readback = compiledIndex(good, p.readback);
  const int gtao = compiledIndex(good, p.gtao);
  const int recon = compiledIndex(good, p.reconstructNormals);

  const auto fails = [&](const CompiledGraph& bad, const char* what) {
    ::testing::TestPartResultArray results;
    {
      ::testing::ScopedFakeTestPartResultReporter reporter(
          ::testing::ScopedFakeTestPartResultReporter::INTERCEPT_ONLY_CURRENT_THREAD, &results);
      checkCompiled(p.graph, bad);
    }
    EXPECT_GT(results.size(), 0) << "checker accepted: " << what;
  };
  {
    CompiledGraph bad = good;  // drop the RAW barrier before the read-back
    bad.passes[readback].barriersBefore.clear();
    fails(bad, "missing RAW barrier");
  }
  {
    CompiledGraph bad = good;  // RAW barrier whose src misses the writer's stage
    for (Barrier& b : bad.passes[readback].barriersBefore) b.before.stage = VK_PIPELINE_STAGE_2_COPY_BIT;
    fails(bad, "wrong src stage");
  }
  {
    CompiledGraph bad = good;  // reuse of normals' memory without waiting for gtao's read
    for (Barrier& b : bad.passes[spatial].barriersBefore) {
      if (b.resource == p.aoBlurred) b.before = kFresh;
    }
    fails(bad, "memory reuse without waiting");
  }
  {
    CompiledGraph bad = good;  // needless barrier between two sampled reads of view_depth
    bad.passes[gtao].barriersBefore.push_back(Barrier{p.viewDepth, kSampled, kSampled});
    fails(bad, "read-after-read barrier");
  }
  {
    CompiledGraph bad = good;  // wrong layout for a read
    for (Barrier& b : bad.passes[recon].barriersBefore) {
      if (b.resource == p.viewDepth) b.after.layout = VK_IMAGE_LAYOUT_GENERAL;
    }
    fails(bad, "wrong layout");
  }
  {
    CompiledGraph bad = good;  // overlapping slot members
    bad.resources[p.aoNoisy].memorySlot = bad.resources[p.aoBlurred].memorySlot;
    bad.slots[bad.resources[p.aoBlurred].memorySlot].resources.push_back(p.aoNoisy);
    fails(bad, "overlapping aliases");
  }
  {
    CompiledGraph bad = good;  // wrong final state
    bad.resources[p.history.current].finalState = kStorageWrite;
    fails(bad, "wrong finalState");
  }
}

TEST(GraphBarriers, RandomGraphsPassTheChecker) {
  size_t barriers = 0, transitionsBetweenReads = 0;
  for (uint32_t seed = 1000; seed < 1200; ++seed) {
    SCOPED_TRACE(::testing::Message() << "random graph seed " << seed);
    RandomGraph r = randomGraph(seed);
    const CompiledGraph c = r.graph.compile();
    checkCompiled(r.graph, c);
    if (HasFailure()) {
      ADD_FAILURE() << describe(r.graph, c);
      return;
    }
    for (const CompiledPass& p : c.passes) {
      barriers += p.barriersBefore.size();
      for (const Barrier& b : p.barriersBefore) {
        transitionsBetweenReads += b.before.access != 0 &&
                                   !(b.before.access & (VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                                                        VK_ACCESS_2_TRANSFER_WRITE_BIT)) &&
                                   !(b.after.access & (VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                                                       VK_ACCESS_2_TRANSFER_WRITE_BIT));
      }
    }
  }
  EXPECT_GT(barriers, 500u);
  EXPECT_GT(transitionsBetweenReads, 20u);
}

}  // namespace
}  // namespace aor::graph::testing
