// The graph's capacity beyond one-level images: mip levels and array layers (producers, culling and
// barriers per subresource, merged into ranges), buffers (hazards without layouts) and writes made
// only when read. No GPU: tests/runtime/graph_capacity_test.cpp runs the same shapes on lavapipe.
#include <gtest/gtest.h>

#include "graph/render_graph.h"

namespace aor::graph {
namespace {

constexpr VkFormat kR16F = VK_FORMAT_R16_SFLOAT;

int indexOf(const CompiledGraph& c, uint32_t pass) {
  for (size_t i = 0; i < c.passes.size(); ++i)
    if (c.passes[i].pass == pass) return int(i);
  return -1;
}

const std::vector<Barrier>& barriersOf(const CompiledGraph& c, uint32_t pass) {
  int i = indexOf(c, pass);
  EXPECT_GE(i, 0);
  return c.passes.at(size_t(i)).barriersBefore;
}

uint32_t readback(RenderGraph& g, ResourceId id) {
  return g.addPass("readback", [&](PassBuilder& b) {
    b.read(id, Access::TransferRead);
    b.sideEffect();
  });
}

// mip 0 written, then each level i from level i - 1 (as SAO's pyramid does), then all read.
struct MipChain {
  RenderGraph g;
  ResourceId chain = kNoResource, out = kNoResource;
  uint32_t base = 0, minify[4] = {}, reader = 0;
};

MipChain mipChain(uint32_t levelsRead = 5) {
  MipChain m;
  m.chain = m.g.createImage("chain", {64, 32, kR16F, 5});
  m.out = m.g.createImage("out", {64, 32, kR16F});
  m.base = m.g.addPass("base", [&](PassBuilder& b) { b.write(m.chain, Access::StorageWrite, Subresources::mip(0)); });
  for (uint32_t level = 1; level < 5; ++level)
    m.minify[level - 1] = m.g.addPass("minify", [&](PassBuilder& b) {
      b.read(m.chain, Access::SampledRead, Subresources::mip(level - 1));
      b.write(m.chain, Access::StorageWrite, Subresources::mip(level));
    });
  m.reader = m.g.addPass("reader", [&](PassBuilder& b) {
    b.read(m.chain, Access::SampledRead, {0, levelsRead});
    b.write(m.out);
  });
  readback(m.g, m.out);
  return m;
}

TEST(Subresources, EveryLevelOfAMipChainHasItsOwnProducer) {
  auto m = mipChain();
  auto c = m.g.compile();
  EXPECT_TRUE(c.culled.empty()) << "a reader of all levels needs every minify pass";
  EXPECT_EQ(c.passes.size(), 7u);
}

TEST(Subresources, AWriterOfALevelNobodyReadsIsCulled) {
  auto m = mipChain(3);  // the reader takes levels 0-2; level 3 feeds only level 4's pass
  auto c = m.g.compile();
  ASSERT_EQ(c.culled.size(), 2u);
  EXPECT_EQ(c.culled[0].pass, m.minify[2]);
  EXPECT_EQ(c.culled[1].pass, m.minify[3]);
  EXPECT_NE(c.culled[0].reason.find("read only by culled pass minify"), std::string::npos) << c.culled[0].reason;
}

TEST(Subresources, BarriersAreDerivedPerLevel) {
  auto m = mipChain();
  auto c = m.g.compile();
  for (uint32_t level = 1; level < 5; ++level) {
    const auto& b = barriersOf(c, m.minify[level - 1]);
    ASSERT_EQ(b.size(), 2u) << "level " << level;
    // The level read: from this frame's storage write to a sampled read, the layout changing.
    EXPECT_EQ(b[0].range, (Subresources{level - 1, 1, 0, 1}));
    EXPECT_EQ(b[0].before.layout, VK_IMAGE_LAYOUT_GENERAL);
    EXPECT_EQ(b[0].before.access, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    EXPECT_EQ(b[0].after.layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    EXPECT_EQ(b[0].after.access, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    // The level written: first touched here, so from UNDEFINED, waiting for nothing.
    EXPECT_EQ(b[1].range, (Subresources{level, 1, 0, 1}));
    EXPECT_EQ(b[1].before.layout, VK_IMAGE_LAYOUT_UNDEFINED);
    EXPECT_EQ(b[1].before.stage, VK_PIPELINE_STAGE_2_NONE);
    EXPECT_EQ(b[1].after.layout, VK_IMAGE_LAYOUT_GENERAL);
  }
  // Levels 0-3 are already readable by the sampler; only level 4 waits for its writer.
  const auto& r = barriersOf(c, m.reader);
  std::vector<Barrier> chainBarriers;
  for (const auto& b : r)
    if (b.resource == m.chain) chainBarriers.push_back(b);
  ASSERT_EQ(chainBarriers.size(), 1u);
  EXPECT_EQ(chainBarriers[0].range, (Subresources{4, 1, 0, 1}));
  for (const auto& state : c.resources[m.chain].finalStates)
    EXPECT_EQ(state.layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
}

TEST(Subresources, OneBarrierCoversLevelsInTheSameState) {
  RenderGraph g;
  auto chain = g.createImage("chain", {64, 32, kR16F, 5});
  auto out = g.createImage("out", {64, 32, kR16F});
  g.addPass("prefilter", [&](PassBuilder& b) { b.write(chain); });  // every level in one dispatch, as XeGTAO's
  uint32_t reader = g.addPass("main", [&](PassBuilder& b) {
    b.read(chain);
    b.write(out);
  });
  readback(g, out);
  auto c = g.compile();
  ASSERT_EQ(barriersOf(c, 0).size(), 1u);
  EXPECT_EQ(barriersOf(c, 0)[0].range, (Subresources{0, 5, 0, 1}));
  const auto& b = barriersOf(c, reader);
  ASSERT_EQ(b.size(), 2u);  // chain (all five levels at once) and out
  EXPECT_EQ(b[0].resource, chain);
  EXPECT_EQ(b[0].range, (Subresources{0, 5, 0, 1}));
}

TEST(Subresources, LayersWrittenByDifferentPassesAreReadBehindOneBarrier) {
  RenderGraph g;
  auto layers = g.createImage("deinterleaved", {32, 16, kR16F, 1, 4});
  auto out = g.createImage("out", {64, 32, kR16F});
  uint32_t writers[4];
  for (uint32_t layer = 0; layer < 4; ++layer)
    writers[layer] = g.addPass("generate", [&](PassBuilder& b) { b.write(layers, Access::StorageWrite, Subresources::layer(layer)); });
  uint32_t apply = g.addPass("apply", [&](PassBuilder& b) {
    b.read(layers, Access::SampledRead);
    b.write(out);
  });
  readback(g, out);
  auto c = g.compile();
  EXPECT_TRUE(c.culled.empty());
  // Each writer transitions only its own layer.
  for (uint32_t layer = 0; layer < 4; ++layer) {
    ASSERT_EQ(barriersOf(c, writers[layer]).size(), 1u);
    EXPECT_EQ(barriersOf(c, writers[layer])[0].range, (Subresources{0, 1, layer, 1}));
  }
  const auto& b = barriersOf(c, apply);
  ASSERT_EQ(b.size(), 2u);
  EXPECT_EQ(b[0].range, (Subresources{0, 1, 0, 4}));
  EXPECT_EQ(b[0].before.access, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}

TEST(Subresources, ReadingALevelNoPassWroteIsAnError) {
  RenderGraph g;
  auto chain = g.createImage("chain", {64, 32, kR16F, 3});
  g.addPass("base", [&](PassBuilder& b) { b.write(chain, Access::StorageWrite, Subresources::mip(0)); });
  g.addPass("reader", [&](PassBuilder& b) {
    b.read(chain, Access::SampledRead, Subresources::mip(2));
    b.sideEffect();
  });
  try {
    g.compile();
    FAIL() << "compile() accepted a read of an unwritten level";
  } catch (const std::logic_error& e) {
    EXPECT_NE(std::string(e.what()).find("'chain' mip 2 before any earlier pass writes it"), std::string::npos) << e.what();
  }
}

TEST(Subresources, RangesOutsideTheImageAndImpossibleChainsAreRefused) {
  RenderGraph g;
  EXPECT_THROW(g.createImage("too_deep", {8, 8, kR16F, 5}), std::invalid_argument);  // 8x8 has 4 levels
  auto image = g.createImage("image", {8, 8, kR16F, 2});
  EXPECT_THROW(g.addPass("p", [&](PassBuilder& b) { b.write(image, Access::StorageWrite, Subresources::mip(2)); }),
               std::invalid_argument);
  EXPECT_THROW(g.addPass("p", [&](PassBuilder& b) { b.write(image, Access::StorageWrite, Subresources::layer(1)); }),
               std::invalid_argument);
  EXPECT_TRUE(g.passes().empty());
  EXPECT_EQ(imageBytes({8, 8, kR16F, 2}), (64u + 16u) * 2u);
  EXPECT_EQ(imageBytes({8, 8, kR16F, 1, 3}), 64u * 2u * 3u);
}

TEST(Subresources, AnAliasedImageWaitsForItsSlotPredecessorOnEveryLevel) {
  RenderGraph g;
  auto first = g.createImage("first", {64, 32, VK_FORMAT_R32_SFLOAT});
  auto chain = g.createImage("chain", {64, 32, kR16F, 3});
  auto out = g.createImage("out", {64, 32, VK_FORMAT_R32_SFLOAT});
  g.addPass("a", [&](PassBuilder& b) { b.write(first); });
  g.addPass("b", [&](PassBuilder& b) {
    b.read(first, Access::StorageRead);
    b.write(out);
  });
  uint32_t base = g.addPass("base", [&](PassBuilder& b) {
    b.read(out, Access::StorageRead);
    b.write(chain, Access::StorageWrite, Subresources::mip(0));
  });
  uint32_t minify = g.addPass("minify", [&](PassBuilder& b) {
    b.read(chain, Access::SampledRead, Subresources::mip(0));
    b.write(chain, Access::StorageWrite, {1, 2});
  });
  g.addPass("final", [&](PassBuilder& b) {
    b.read(chain, Access::TransferRead);
    b.sideEffect();
  });
  auto c = g.compile();
  ASSERT_EQ(c.resources[chain].memorySlot, c.resources[first].memorySlot) << "chain should reuse first's memory";
  // At its first use every level waits for `first`'s reader; the untouched levels move to GENERAL.
  const auto& b = barriersOf(c, base);
  std::vector<Barrier> chainBarriers;
  for (const auto& x : b)
    if (x.resource == chain) chainBarriers.push_back(x);
  ASSERT_EQ(chainBarriers.size(), 2u);
  EXPECT_EQ(chainBarriers[0].range, (Subresources{0, 1, 0, 1}));
  EXPECT_EQ(chainBarriers[1].range, (Subresources{1, 2, 0, 1}));
  for (const auto& x : chainBarriers) {
    EXPECT_EQ(x.before.stage, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    EXPECT_EQ(x.before.access, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    EXPECT_EQ(x.before.layout, VK_IMAGE_LAYOUT_UNDEFINED);
  }
  EXPECT_EQ(chainBarriers[1].after.layout, VK_IMAGE_LAYOUT_GENERAL);
  // The later write of levels 1-2 still waits on the transition (a write after a "write").
  bool levelsBarriered = false;
  for (const auto& x : barriersOf(c, minify))
    levelsBarriered |= x.resource == chain && x.range == Subresources{1, 2, 0, 1} &&
                       x.before.stage == VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
  EXPECT_TRUE(levelsBarriered);
}

TEST(Buffers, HazardsGetBufferBarriersWithoutLayouts) {
  RenderGraph g;
  auto counter = g.createBuffer("counter", {4});
  auto out = g.createImage("out", {16, 16, kR16F});
  uint32_t clear = g.addPass("clear", [&](PassBuilder& b) { b.write(counter, Access::ClearWrite); });
  uint32_t count = g.addPass("count", [&](PassBuilder& b) {
    b.read(counter, Access::StorageRead);
    b.write(counter, Access::StorageWrite);
  });
  uint32_t use = g.addPass("use", [&](PassBuilder& b) {
    b.read(counter, Access::UniformRead);
    b.write(out);
  });
  readback(g, out);
  auto c = g.compile();
  EXPECT_TRUE(c.culled.empty());
  EXPECT_TRUE(barriersOf(c, clear).empty()) << "a fresh transient buffer has nothing to wait for";
  ASSERT_EQ(barriersOf(c, count).size(), 1u);
  const Barrier& afterClear = barriersOf(c, count)[0];
  EXPECT_EQ(afterClear.before.stage, VK_PIPELINE_STAGE_2_CLEAR_BIT | VK_PIPELINE_STAGE_2_COPY_BIT) << "fill: clear or copy";
  EXPECT_EQ(afterClear.after.access, VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  EXPECT_EQ(afterClear.after.layout, VK_IMAGE_LAYOUT_UNDEFINED);
  std::vector<Barrier> counterBarriers;
  for (const auto& x : barriersOf(c, use))
    if (x.resource == counter) counterBarriers.push_back(x);
  ASSERT_EQ(counterBarriers.size(), 1u);
  EXPECT_EQ(counterBarriers[0].after.access, VK_ACCESS_2_UNIFORM_READ_BIT);
  EXPECT_EQ(c.resources[counter].bufferUsage,
            VkBufferUsageFlags(VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                               VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT));
  EXPECT_EQ(c.resources[counter].usage, 0u);
}

TEST(Buffers, WriteAfterReadWaitsAndBuffersNeverShareImageMemory) {
  RenderGraph g;
  auto bvh = g.importBuffer("bvh", {1024}, {VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT});
  auto scratch = g.createImage("scratch", {16, 16, VK_FORMAT_R32_SFLOAT});
  auto counts = g.createBuffer("counts", {1024});
  uint32_t trace = g.addPass("trace", [&](PassBuilder& b) {
    b.read(bvh, Access::StorageRead);
    b.write(scratch);
  });
  g.addPass("refit", [&](PassBuilder& b) {
    b.read(scratch, Access::StorageRead);
    b.write(bvh, Access::StorageWrite);
    b.write(counts, Access::StorageWrite);
    b.sideEffect();
  });
  auto c = g.compile();
  ASSERT_EQ(barriersOf(c, trace).size(), 2u);  // the imported buffer's pending copy, scratch's first use
  EXPECT_EQ(barriersOf(c, trace)[0].before.access, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  bool war = false;
  for (const auto& x : barriersOf(c, 1))
    war |= x.resource == bvh && x.before.access == VK_ACCESS_2_SHADER_STORAGE_READ_BIT &&
           x.after.access == VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
  EXPECT_TRUE(war) << "the refit's write must wait for the trace's read";
  EXPECT_NE(c.resources[counts].memorySlot, c.resources[scratch].memorySlot);
  EXPECT_EQ(c.persistentBytes, 1024u);
}

TEST(Buffers, ImageOnlyAndBufferOnlyAccessesAreRefused) {
  RenderGraph g;
  auto buffer = g.createBuffer("buffer", {16});
  auto image = g.createImage("image", {4, 4, kR16F});
  EXPECT_THROW(g.addPass("p", [&](PassBuilder& b) { b.read(buffer, Access::SampledRead); }), std::invalid_argument);
  EXPECT_THROW(g.addPass("p", [&](PassBuilder& b) { b.read(image, Access::UniformRead); }), std::invalid_argument);
  EXPECT_THROW(g.createBuffer("empty", {0}), std::invalid_argument);
}

TEST(WriteIfRead, AnUnreadWriteIsDroppedAndItsResourceNeverAllocated) {
  RenderGraph g;
  auto depth = g.createImage("depth", {16, 16, VK_FORMAT_R32_SFLOAT});
  auto depth2 = g.createImage("depth2", {16, 16, VK_FORMAT_R32_SFLOAT});
  auto out = g.createImage("out", {16, 16, kR16F});
  uint32_t upload = g.addPass("upload", [&](PassBuilder& b) {
    b.writeIfRead(depth, Access::TransferWrite);
    b.writeIfRead(depth2, Access::TransferWrite);
  });
  g.addPass("ao", [&](PassBuilder& b) {
    b.read(depth, Access::StorageRead);
    b.write(out);
  });
  readback(g, out);
  auto c = g.compile();
  ASSERT_EQ(indexOf(c, upload), 0);
  EXPECT_EQ(c.passes[0].accessLive, (std::vector<bool>{true, false}));
  EXPECT_TRUE(c.resources[depth].used);
  EXPECT_FALSE(c.resources[depth2].used);
  ASSERT_EQ(c.passes[0].barriersBefore.size(), 1u);
  EXPECT_EQ(c.passes[0].barriersBefore[0].resource, depth);
  EXPECT_EQ(c.unaliasedTransientBytes, 16u * 16u * (4u + 2u));
}

}  // namespace
}  // namespace aor::graph
