#pragma once
// Shared helpers for the render-graph tests: the AO pipeline graph in several shapes, a checker that
// re-derives every property of a CompiledGraph independently (culling, lifetimes, aliasing, and a
// synchronisation simulation of the barriers), and a seeded random DAG generator.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include <unistd.h>

#include "graph/render_graph.h"

namespace aor::graph::testing {

// ---------------------------------------------------------------------------------------------
// The pipeline graph

enum class Readback { Noisy, Blurred, Temporal };

struct PipelineOptions {
  bool normalsImported = false;   // gtao reads an imported normal buffer instead of reconstructing
  bool historyValid = true;       // temporal reads last frame's history
  bool edgeWeights = false;       // spatial also reads "edge_weights" produced by its own pass
  Readback readback = Readback::Temporal;
  uint32_t width = 1920;
  uint32_t height = 1080;
  ResourceState historyPreviousState{VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                                  VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL};
  ResourceState historyCurrentState{};
};

struct Pipeline {
  RenderGraph graph;
  ResourceId depthRaw = kNoResource, viewDepth = kNoResource, normalsImported = kNoResource,
             normalsReconstructed = kNoResource, edgeWeights = kNoResource, aoNoisy = kNoResource,
             aoBlurred = kNoResource;
  HistoryPair history;
  uint32_t upload = 0, linearize = 0, reconstructNormals = 0, edgeWeightsPass = 0, gtao = 0,
           spatial = 0, temporal = 0, readback = 0;
};

inline Pipeline buildPipeline(const PipelineOptions& o = {}) {
  Pipeline p;
  RenderGraph& g = p.graph;
  const auto desc = [&](VkFormat f) { return ImageDesc{o.width, o.height, f}; };
  p.depthRaw = g.importImage("depth_raw", desc(VK_FORMAT_R32_SFLOAT));
  if (o.normalsImported) {
    p.normalsImported = g.importImage(
        "normals", desc(VK_FORMAT_A2B10G10R10_UNORM_PACK32),
        {VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
         VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL});
  }
  p.viewDepth = g.createImage("view_depth", desc(VK_FORMAT_R32_SFLOAT));
  p.normalsReconstructed =
      g.createImage("normals_reconstructed", desc(VK_FORMAT_A2B10G10R10_UNORM_PACK32));
  p.aoNoisy = g.createImage("ao_noisy", desc(VK_FORMAT_R8_UNORM));
  if (o.edgeWeights) p.edgeWeights = g.createImage("edge_weights", desc(VK_FORMAT_R8G8_UNORM));
  p.aoBlurred = g.createImage("ao_blurred", desc(VK_FORMAT_R16_SFLOAT));
  p.history = g.createHistory("ao_history", desc(VK_FORMAT_R16G16_SFLOAT), o.historyValid,
                              o.historyPreviousState, o.historyCurrentState);

  p.upload = g.addPass("upload", [&](PassBuilder& b) { b.write(p.depthRaw, Access::TransferWrite); });
  p.linearize = g.addPass("linearize", [&](PassBuilder& b) {
    b.read(p.depthRaw);
    b.write(p.viewDepth);
  });
  p.reconstructNormals = g.addPass("reconstruct_normals", [&](PassBuilder& b) {
    b.read(p.viewDepth);
    b.write(p.normalsReconstructed);
  });
  const ResourceId normals = o.normalsImported ? p.normalsImported : p.normalsReconstructed;
  p.gtao = g.addPass("gtao", [&](PassBuilder& b) {
    b.read(p.viewDepth);
    b.read(normals);
    b.write(p.aoNoisy);
  });
  if (o.edgeWeights) {
    p.edgeWeightsPass = g.addPass("edge_weights", [&](PassBuilder& b) {
      b.read(p.viewDepth);
      b.write(p.edgeWeights);
    });
  }
  p.spatial = g.addPass("spatial", [&](PassBuilder& b) {
    b.read(p.aoNoisy);
    b.read(p.viewDepth);
    if (o.edgeWeights) b.read(p.edgeWeights);
    b.write(p.aoBlurred);
  });
  p.temporal = g.addPass("temporal", [&](PassBuilder& b) {
    b.read(p.aoBlurred);
    b.read(p.viewDepth);
    if (p.history.previous != kNoResource) b.read(p.history.previous);
    b.write(p.history.current);
  });
  const ResourceId final = o.readback == Readback::Noisy     ? p.aoNoisy
                           : o.readback == Readback::Blurred ? p.aoBlurred
                                                             : p.history.current;
  p.readback = g.addPass("readback", [&](PassBuilder& b) {
    b.read(final, Access::TransferRead);
    b.sideEffect();
  });
  return p;
}

// ---------------------------------------------------------------------------------------------
// Lookup helpers

inline int compiledIndex(const CompiledGraph& c, uint32_t pass) {
  for (size_t i = 0; i < c.passes.size(); ++i) {
    if (c.passes[i].pass == pass) return static_cast<int>(i);
  }
  return -1;
}
inline bool isCulled(const CompiledGraph& c, uint32_t pass) {
  return std::any_of(c.culled.begin(), c.culled.end(),
                     [&](const CulledPass& cp) { return cp.pass == pass; });
}
inline std::string culledReason(const CompiledGraph& c, uint32_t pass) {
  for (const CulledPass& cp : c.culled) {
    if (cp.pass == pass) return cp.reason;
  }
  return {};
}
inline std::vector<Barrier> barriersOn(const CompiledGraph& c, uint32_t pass, ResourceId id) {
  std::vector<Barrier> out;
  const int index = compiledIndex(c, pass);
  if (index < 0) return out;
  for (const Barrier& b : c.passes[index].barriersBefore) {
    if (b.resource == id) out.push_back(b);
  }
  return out;
}
inline size_t barrierCount(const CompiledGraph& c, ResourceId id) {
  size_t n = 0;
  for (const CompiledPass& p : c.passes) {
    for (const Barrier& b : p.barriersBefore) n += b.resource == id;
  }
  return n;
}
inline bool sameState(const ResourceState& a, const ResourceState& b) {
  return a.stage == b.stage && a.access == b.access && a.layout == b.layout;
}
inline std::string stateText(const ResourceState& s) {
  return stageNames(s.stage) + "/" + accessNames(s.access) + "/" + layoutName(s.layout);
}

// ---------------------------------------------------------------------------------------------
// Independent checker

namespace detail {

inline bool subset(uint64_t part, uint64_t whole) { return (part & ~whole) == 0; }

struct Op {  // one declared access of a live pass
  int pass;  // compiled index
  VkPipelineStageFlags2 stage;
  VkAccessFlags2 access;
  bool write;
  VkImageLayout layout;  // requiredState(access).layout
};
struct Bar {
  int pass;  // compiled index
  ResourceId resource;
  Barrier barrier;
};
struct Point {  // an access, or the layout transition performed by barrier `barrier`
  bool isTransition = false;
  int barrier = -1;
  Op op{};
};

// Is there a chain of barriers from `x` to `y` (execution dependency; with `memory`, also an
// availability operation covering x and a visibility operation covering y)? Barriers in `bars` are
// sorted by pass; barriers before the same pass do not chain with each other.
inline bool ordered(const std::vector<Bar>& bars, const Point& x, const Point& y, bool memory) {
  const size_t n = bars.size();
  std::vector<char> reach(n, 0), avail(n, 0);
  for (size_t k = 0; k < n; ++k) {
    const Bar& b = bars[k];
    const bool afterX = x.isTransition ? static_cast<int>(k) >= x.barrier : b.pass > x.op.pass;
    const bool beforeY = y.isTransition ? static_cast<int>(k) <= y.barrier : b.pass <= y.op.pass;
    if (!afterX || !beforeY) continue;
    bool r = false, a = false;
    const bool coversX = !x.isTransition && subset(x.op.stage, b.barrier.before.stage);
    const bool availX = !memory || x.isTransition || subset(x.op.access, b.barrier.before.access);
    if (x.isTransition) {
      if (static_cast<int>(k) == x.barrier) r = a = true;
    } else if (coversX) {
      r = true;
      a = availX;
    }
    if (!(x.isTransition && static_cast<int>(k) == x.barrier)) {
      for (size_t j = 0; j < k; ++j) {
        if (reach[j] && bars[j].pass < b.pass &&
            (bars[j].barrier.after.stage & b.barrier.before.stage) != 0) {
          r = true;
          a = a || avail[j] || (!x.isTransition && availX);
        }
      }
    }
    reach[k] = r;
    avail[k] = r && (a || !memory);
  }
  if (y.isTransition) return reach[y.barrier] && avail[y.barrier];
  for (size_t k = 0; k < n; ++k) {
    if (!reach[k] || bars[k].pass > y.op.pass) continue;
    const ResourceState& dst = bars[k].barrier.after;
    if (!subset(y.op.stage, dst.stage)) continue;
    if (memory && (!avail[k] || !subset(y.op.access, dst.access))) continue;
    return true;
  }
  return false;
}

inline std::vector<Bar> sortedBars(std::vector<Bar> bars) {
  std::stable_sort(bars.begin(), bars.end(), [](const Bar& a, const Bar& b) { return a.pass < b.pass; });
  return bars;
}

}  // namespace detail

// Verifies every documented property of `c` against `g`; reports failures through gtest.
inline void checkCompiled(const RenderGraph& g, const CompiledGraph& c) {
  using namespace detail;
  const auto& passes = g.passes();
  const auto& res = g.resources();
  ASSERT_EQ(c.resources.size(), res.size());

  // --- Culling oracle (fixed point over "nearest earlier writer" edges).
  std::vector<std::vector<std::pair<ResourceId, int>>> producers(passes.size());
  {
    std::vector<int> lastWriter(res.size(), -1);
    for (size_t p = 0; p < passes.size(); ++p) {
      for (const auto& [id, a, range_, ifRead_] : passes[p].accesses) {
        if (!isWrite(a)) producers[p].emplace_back(id, lastWriter[id]);
      }
      for (const auto& [id, a, range_, ifRead_] : passes[p].accesses) {
        if (isWrite(a)) lastWriter[id] = static_cast<int>(p);
      }
    }
  }
  std::vector<bool> live(passes.size(), false);
  for (bool changed = true; changed;) {
    changed = false;
    for (size_t p = 0; p < passes.size(); ++p) {
      bool l = passes[p].sideEffect;
      for (size_t q = p + 1; q < passes.size() && !l; ++q) {
        if (!live[q]) continue;
        for (const auto& [id, prod] : producers[q]) l = l || prod == static_cast<int>(p);
      }
      if (l && !live[p]) live[p] = changed = true;
    }
  }
  std::vector<int> seen(passes.size(), 0);
  int previous = -1;
  for (const CompiledPass& cp : c.passes) {
    ASSERT_LT(cp.pass, passes.size());
    EXPECT_GT(static_cast<int>(cp.pass), previous) << "live passes must keep declaration order";
    previous = static_cast<int>(cp.pass);
    ++seen[cp.pass];
    EXPECT_TRUE(live[cp.pass]) << "pass " << passes[cp.pass].name << " should have been culled";
  }
  for (const CulledPass& cp : c.culled) {
    ASSERT_LT(cp.pass, passes.size());
    ++seen[cp.pass];
    EXPECT_FALSE(live[cp.pass]) << "live pass " << passes[cp.pass].name << " was culled";
    EXPECT_FALSE(cp.reason.empty());
    bool writes = false;
    for (const auto& [id, a, range_, ifRead_] : passes[cp.pass].accesses) {
      if (!isWrite(a)) continue;
      writes = true;
      EXPECT_NE(cp.reason.find(res[id].name), std::string::npos)
          << "reason '" << cp.reason << "' of " << passes[cp.pass].name << " omits output "
          << res[id].name;
    }
    if (!writes) {
      EXPECT_EQ(cp.reason, "no outputs and no side effects");
    }
  }
  for (size_t p = 0; p < passes.size(); ++p) {
    EXPECT_EQ(seen[p], 1) << "pass " << passes[p].name << " must be either run or culled";
  }

  // --- Lifetimes, usage.
  std::vector<std::vector<Op>> ops(res.size());
  for (size_t i = 0; i < c.passes.size(); ++i) {
    for (const auto& [id, a, range_, ifRead_] : passes[c.passes[i].pass].accesses) {
      const ResourceState need = requiredState(a);
      ops[id].push_back(Op{static_cast<int>(i), need.stage, need.access, isWrite(a), need.layout});
    }
  }
  uint64_t unaliased = 0, persistent = 0;
  for (ResourceId id = 0; id < res.size(); ++id) {
    const CompiledResource& r = c.resources[id];
    SCOPED_TRACE("resource " + res[id].name);
    EXPECT_EQ(r.used, !ops[id].empty());
    if (!r.used) {
      EXPECT_EQ(r.memorySlot, -1);
      EXPECT_EQ(r.usage, 0u);
      if (res[id].kind != ResourceKind::Transient) {
        EXPECT_TRUE(sameState(r.finalState, res[id].initialState));
      }
      continue;
    }
    EXPECT_EQ(r.firstPass, ops[id].front().pass);
    EXPECT_EQ(r.lastPass, ops[id].back().pass);
    VkImageUsageFlags usage = 0;
    for (const CompiledPass& cp : c.passes) {
      for (const auto& [rid, a, range_, ifRead_] : passes[cp.pass].accesses) {
        if (rid != id) continue;
        switch (a) {
          case Access::SampledRead: usage |= VK_IMAGE_USAGE_SAMPLED_BIT; break;
          case Access::StorageRead:
          case Access::StorageWrite: usage |= VK_IMAGE_USAGE_STORAGE_BIT; break;
          case Access::TransferRead: usage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT; break;
          case Access::TransferWrite:
          case Access::ClearWrite: usage |= VK_IMAGE_USAGE_TRANSFER_DST_BIT; break;
          case Access::UniformRead:
          case Access::IndirectRead:
          case Access::AccelerationStructureRead: ADD_FAILURE() << "buffer access on an image"; break;
        }
      }
    }
    EXPECT_EQ(r.usage, usage);
    if (res[id].kind == ResourceKind::Transient) {
      unaliased += imageBytes(res[id].desc);
      EXPECT_GE(r.memorySlot, 0);
    } else {
      persistent += imageBytes(res[id].desc);
      EXPECT_EQ(r.memorySlot, -1) << "imported/history resources are never aliased";
    }
  }
  EXPECT_EQ(c.unaliasedTransientBytes, unaliased);
  EXPECT_EQ(c.persistentBytes, persistent);

  // --- Slots: membership, disjoint lifetimes (every pair), sizes.
  uint64_t slotBytes = 0;
  std::vector<int> slotOf(res.size(), -1);
  for (size_t s = 0; s < c.slots.size(); ++s) {
    const MemorySlot& slot = c.slots[s];
    EXPECT_FALSE(slot.resources.empty());
    uint64_t largest = 0;
    for (size_t m = 0; m < slot.resources.size(); ++m) {
      const ResourceId id = slot.resources[m];
      ASSERT_LT(id, res.size());
      EXPECT_EQ(res[id].kind, ResourceKind::Transient) << res[id].name << " is in a slot";
      EXPECT_TRUE(c.resources[id].used) << res[id].name;
      EXPECT_EQ(c.resources[id].memorySlot, static_cast<int>(s)) << res[id].name;
      EXPECT_EQ(slotOf[id], -1) << res[id].name << " is in two slots";
      slotOf[id] = static_cast<int>(s);
      largest = std::max(largest, imageBytes(res[id].desc));
      for (size_t o = 0; o < m; ++o) {
        const CompiledResource& a = c.resources[slot.resources[o]];
        const CompiledResource& b = c.resources[id];
        EXPECT_TRUE(a.lastPass < b.firstPass || b.lastPass < a.firstPass)
            << res[slot.resources[o]].name << " [" << a.firstPass << "," << a.lastPass << "] and "
            << res[id].name << " [" << b.firstPass << "," << b.lastPass << "] share slot " << s;
        EXPECT_LT(a.lastPass, b.firstPass) << "slot members must be in order of first use";
      }
    }
    EXPECT_EQ(slot.bytes, largest);
    slotBytes += slot.bytes;
  }
  EXPECT_EQ(c.transientBytes, slotBytes);
  EXPECT_LE(c.transientBytes, c.unaliasedTransientBytes);
  EXPECT_EQ(c.peakBytes(), c.transientBytes + c.persistentBytes);

  // --- Barriers: collect per resource, check placement and `after` states.
  std::vector<std::vector<Bar>> bars(res.size());
  for (size_t i = 0; i < c.passes.size(); ++i) {
    const PassDecl& pass = passes[c.passes[i].pass];
    std::set<ResourceId> barriered;
    for (const Barrier& b : c.passes[i].barriersBefore) {
      ASSERT_LT(b.resource, res.size());
      EXPECT_TRUE(barriered.insert(b.resource).second)
          << "two barriers on " << res[b.resource].name << " before " << pass.name;
      const ResourceState need = requiredState(pass, b.resource);
      EXPECT_NE(need.access, VK_ACCESS_2_NONE)
          << "barrier on " << res[b.resource].name << " before " << pass.name
          << ", which does not access it";
      EXPECT_TRUE(sameState(b.after, need))
          << "barrier on " << res[b.resource].name << " before " << pass.name << ": after="
          << stateText(b.after) << ", pass needs " << stateText(need);
      bars[b.resource].push_back(Bar{static_cast<int>(i), b.resource, b});
    }
  }

  for (ResourceId id = 0; id < res.size(); ++id) {
    if (!c.resources[id].used) {
      EXPECT_TRUE(bars[id].empty()) << "barriers on unused " << res[id].name;
      continue;
    }
    SCOPED_TRACE("barriers of " + res[id].name);
    const bool transient = res[id].kind == ResourceKind::Transient;
    const std::vector<Op>& o = ops[id];
    const std::vector<Bar>& b = bars[id];

    // Layout simulation: every access happens in its required layout (GENERAL where one pass
    // mixes layouts), every barrier starts from the current layout (or discards a transient's
    // contents on first use).
    VkImageLayout layout = transient ? VK_IMAGE_LAYOUT_UNDEFINED : res[id].initialState.layout;
    size_t bi = 0;
    for (size_t k = 0; k < o.size(); ++k) {
      if (k == 0 || o[k].pass != o[k - 1].pass) {
        for (; bi < b.size() && b[bi].pass <= o[k].pass; ++bi) {
          const Barrier& bar = b[bi].barrier;
          EXPECT_EQ(b[bi].pass, o[k].pass) << "barrier not directly before an access";
          if (bi == 0 && transient) {
            EXPECT_EQ(bar.before.layout, VK_IMAGE_LAYOUT_UNDEFINED) << "first use discards";
            EXPECT_TRUE(o[k].write) << "first use of a transient must write it";
          } else {
            EXPECT_EQ(bar.before.layout, layout) << "barrier before pass " << b[bi].pass
                                                 << " does not start from the current layout";
          }
          if (bi == 0 && !transient && b[bi].pass == o.front().pass) {
            EXPECT_TRUE(sameState(bar.before, res[id].initialState))
                << "first barrier must start from the initial state "
                << stateText(res[id].initialState) << ", got " << stateText(bar.before);
          }
          layout = bar.after.layout;
        }
      }
      if (transient && k == 0) {
        EXPECT_FALSE(b.empty() || b[0].pass != o[0].pass) << "transient first use without barrier";
      }
      std::set<VkImageLayout> passLayouts;
      for (const Op& x : o) {
        if (x.pass == o[k].pass) passLayouts.insert(x.layout);
      }
      const VkImageLayout expected = passLayouts.size() > 1 ? VK_IMAGE_LAYOUT_GENERAL : o[k].layout;
      EXPECT_EQ(layout, expected) << "access in pass " << o[k].pass << " happens in "
                                  << layoutName(layout) << ", needs " << layoutName(expected);
    }

    // Slot predecessor: the first barrier waits for the previous member's final accesses.
    if (transient && slotOf[id] >= 0 && !b.empty()) {
      const auto& members = c.slots[slotOf[id]].resources;
      const auto it = std::find(members.begin(), members.end(), id);
      if (it != members.begin()) {
        const CompiledResource& pred = c.resources[*(it - 1)];
        EXPECT_EQ(b[0].barrier.before.stage, pred.finalState.stage) << "memory reuse hazard";
        EXPECT_EQ(b[0].barrier.before.access, pred.finalState.access) << "memory reuse hazard";
      } else {
        EXPECT_EQ(b[0].barrier.before.stage, VK_PIPELINE_STAGE_2_NONE);
        EXPECT_EQ(b[0].barrier.before.access, VK_ACCESS_2_NONE);
      }
    }

    // Hazards: every conflicting pair of accesses is ordered by a barrier chain. For imported and
    // history images, the work that left the initial state counts as an access before pass 0.
    std::vector<Op> h = o;
    const ResourceState& init = res[id].initialState;
    if (!transient && (init.stage != 0 || init.access != 0)) {
      const VkAccessFlags2 writeBits = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                                       VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_SHADER_WRITE_BIT |
                                       VK_ACCESS_2_MEMORY_WRITE_BIT;
      h.insert(h.begin(), Op{-1, init.stage, init.access, (init.access & writeBits) != 0, init.layout});
    }
    for (size_t x = 0; x < h.size(); ++x) {
      for (size_t y = x + 1; y < h.size(); ++y) {
        if (h[x].pass == h[y].pass || !(h[x].write || h[y].write)) continue;
        Point px, py;
        px.op = h[x];
        py.op = h[y];
        EXPECT_TRUE(ordered(b, px, py, h[x].write))
            << (h[x].write ? (h[y].write ? "WAW" : "RAW") : "WAR") << " hazard between passes "
            << h[x].pass << " and " << h[y].pass << " not covered";
      }
    }
    // Direct RAW rule: between the nearest write and a later read there is a barrier whose
    // `before` covers the writer.
    for (size_t y = 0; y < h.size(); ++y) {
      if (h[y].write) continue;
      int w = -1;
      for (size_t x = 0; x < h.size(); ++x) {
        if (h[x].write && h[x].pass < h[y].pass) w = static_cast<int>(x);
      }
      if (w < 0) continue;
      bool found = false;
      for (const Bar& bar : b) {
        found = found || (bar.pass > h[w].pass && bar.pass <= h[y].pass &&
                          subset(h[w].stage, bar.barrier.before.stage) &&
                          subset(h[w].access, bar.barrier.before.access));
      }
      EXPECT_TRUE(found) << "read in pass " << h[y].pass << " of the write in pass " << h[w].pass;
    }
    // Layout transitions are ordered after earlier accesses and before later ones.
    for (size_t k = 0; k < b.size(); ++k) {
      if (b[k].barrier.before.layout == b[k].barrier.after.layout) continue;
      Point t;
      t.isTransition = true;
      t.barrier = static_cast<int>(k);
      for (const Op& op : h) {
        Point p;
        p.op = op;
        if (op.pass < b[k].pass) {
          EXPECT_TRUE(ordered(b, p, t, op.write))
              << "transition before pass " << b[k].pass << " races with pass " << op.pass;
        } else {
          EXPECT_TRUE(ordered(b, t, p, true))
              << "transition before pass " << b[k].pass << " not visible to pass " << op.pass;
        }
      }
    }
    // No barrier between two reads in the same layout (unless the reader needs more visibility).
    std::vector<int> touching;
    for (const Op& op : o) {
      if (touching.empty() || touching.back() != op.pass) touching.push_back(op.pass);
    }
    for (size_t k = 1; k < touching.size(); ++k) {
      const PassDecl& a = passes[c.passes[touching[k - 1]].pass];
      const PassDecl& p = passes[c.passes[touching[k]].pass];
      const ResourceState sa = requiredState(a, id), sp = requiredState(p, id);
      const bool readsOnly = !(sa.access & (VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                                            VK_ACCESS_2_TRANSFER_WRITE_BIT)) &&
                             !(sp.access & (VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                                            VK_ACCESS_2_TRANSFER_WRITE_BIT));
      if (readsOnly && sa.layout == sp.layout && subset(sp.stage, sa.stage) &&
          subset(sp.access, sa.access)) {
        for (const Bar& bar : b) {
          EXPECT_NE(bar.pass, touching[k]) << "needless barrier between two reads in "
                                           << layoutName(sp.layout) << " before " << p.name;
        }
      }
    }
    // Final state: the layout after the last access, covering the last pass's accesses.
    const CompiledResource& r = c.resources[id];
    EXPECT_EQ(r.finalState.layout, layout);
    const ResourceState last = requiredState(passes[c.passes[o.back().pass].pass], id);
    EXPECT_TRUE(subset(last.stage, r.finalState.stage) && subset(last.access, r.finalState.access))
        << "finalState " << stateText(r.finalState) << " misses the last access " << stateText(last);
    if (last.access & (VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT)) {
      EXPECT_TRUE(sameState(r.finalState, last)) << "after a write, finalState is that write";
    }
  }

  // Memory reuse: every access of an earlier slot member happens before the later member's first
  // barrier (which discards the contents with a layout transition).
  for (const MemorySlot& slot : c.slots) {
    std::vector<Bar> all;
    for (ResourceId id : slot.resources) all.insert(all.end(), bars[id].begin(), bars[id].end());
    all = sortedBars(all);
    for (size_t m = 1; m < slot.resources.size(); ++m) {
      const ResourceId id = slot.resources[m];
      int first = -1;
      for (size_t k = 0; k < all.size(); ++k) {
        if (all[k].resource == id) {
          first = static_cast<int>(k);
          break;
        }
      }
      ASSERT_GE(first, 0);
      Point t;
      t.isTransition = true;
      t.barrier = first;
      for (size_t e = 0; e < m; ++e) {
        for (const Op& op : ops[slot.resources[e]]) {
          Point p;
          p.op = op;
          EXPECT_TRUE(ordered(all, p, t, op.write))
              << res[slot.resources[e]].name << " (pass " << op.pass << ") races with reuse of its "
              << "memory by " << res[id].name;
        }
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Random graphs

struct RandomGraph {
  RenderGraph graph;
  std::vector<HistoryPair> histories;
};

inline RandomGraph randomGraph(uint32_t seed) {
  std::mt19937 rng(seed);
  const auto uni = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  const auto chance = [&](double p) { return std::uniform_real_distribution<double>(0, 1)(rng) < p; };
  static const VkFormat kFormats[] = {VK_FORMAT_R8_UNORM, VK_FORMAT_R16_SFLOAT,
                                      VK_FORMAT_R16G16_SFLOAT, VK_FORMAT_R32_SFLOAT,
                                      VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_R32G32B32A32_SFLOAT};
  static const ResourceState kStates[] = {
      {},
      {VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL},
      {VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL},
      {VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
       VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
      {VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_IMAGE_LAYOUT_GENERAL},
      {VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, VK_IMAGE_LAYOUT_GENERAL},
  };
  const auto desc = [&] {
    return ImageDesc{static_cast<uint32_t>(16 * uni(1, 8)), static_cast<uint32_t>(16 * uni(1, 8)),
                     kFormats[uni(0, 5)]};
  };
  const auto state = [&] { return kStates[uni(0, 5)]; };

  RandomGraph out;
  RenderGraph& g = out.graph;
  std::vector<ResourceId> readable;   // imported and history previous: readable from the start
  std::vector<ResourceId> writable;   // transients, history current, some imported
  for (int i = 0, n = uni(0, 3); i < n; ++i) {
    const ResourceId id = g.importImage("imported" + std::to_string(i), desc(), state());
    readable.push_back(id);
    if (chance(0.3)) writable.push_back(id);
  }
  for (int i = 0, n = uni(0, 2); i < n; ++i) {
    const HistoryPair h = g.createHistory("history" + std::to_string(i), desc(), chance(0.6),
                                          state(), state());
    out.histories.push_back(h);
    if (h.previous != kNoResource) readable.push_back(h.previous);
    writable.push_back(h.current);
  }
  for (int i = 0, n = uni(2, 10); i < n; ++i) {
    writable.push_back(g.createImage("t" + std::to_string(i), desc()));
  }
  std::shuffle(writable.begin(), writable.end(), rng);

  static const Access kReads[] = {Access::SampledRead, Access::StorageRead, Access::TransferRead};
  static const Access kWrites[] = {Access::StorageWrite, Access::TransferWrite, Access::ClearWrite};
  const int passCount = uni(3, 16);
  for (int p = 0; p < passCount; ++p) {
    std::vector<std::pair<ResourceId, Access>> reads, writes;
    if (!readable.empty()) {
      for (int r = 0, n = uni(0, 3); r < n; ++r) {
        reads.emplace_back(readable[uni(0, static_cast<int>(readable.size()) - 1)], kReads[uni(0, 2)]);
      }
    }
    for (int w = 0, n = uni(0, 2); w < n; ++w) {
      ResourceId target = writable[uni(0, static_cast<int>(writable.size()) - 1)];
      if (!reads.empty() && chance(0.15)) target = reads[uni(0, static_cast<int>(reads.size()) - 1)].first;
      writes.emplace_back(target, kWrites[uni(0, 2)]);
    }
    const bool side = chance(0.2) || (p == passCount - 1 && chance(0.8));
    g.addPass("pass" + std::to_string(p), [&](PassBuilder& b) {
      for (const auto& [id, a] : reads) b.read(id, a);
      for (const auto& [id, a] : writes) b.write(id, a);
      if (side) b.sideEffect();
    });
    for (const auto& [id, a] : writes) {
      if (std::find(readable.begin(), readable.end(), id) == readable.end()) readable.push_back(id);
    }
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Graphviz

inline bool haveDot() { return std::system("command -v dot >/dev/null 2>&1") == 0; }

// Runs `dot -Tsvg` on the text; returns its exit status (0 = accepted) and fills `svg`.
inline int runDot(const std::string& text, const std::string& stem, std::string* svg = nullptr) {
  const std::string base = ::testing::TempDir() + stem + "_" + std::to_string(::getpid());
  {
    std::ofstream f(base + ".dot");
    f << text;
  }
  const std::string cmd = "dot -Tsvg '" + base + ".dot' -o '" + base + ".svg' 2>'" + base + ".err'";
  const int rc = std::system(cmd.c_str());
  if (svg) {
    std::ifstream in(base + ".svg");
    svg->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  if (rc == 0) {
    for (const char* ext : {".dot", ".svg", ".err"}) std::remove((base + ext).c_str());
  }
  return rc;
}

}  // namespace aor::graph::testing
