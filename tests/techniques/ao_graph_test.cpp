// The real AO frame graph, compiled without a GPU: which passes and resources a capture and a run
// need (issue "Build only what a scene and a run need"), checked with the graph tests' checker.
#include <memory>
#include <optional>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "../graph/graph_test_support.h"
#include "techniques/built_frame.h"
#include "techniques/gtao/gtao_settings.h"
#include "techniques/registry.h"
#include "vk/context.h"

namespace aor {
namespace {

constexpr const char* kAoHistory = "ao_history";
constexpr const char* kDistanceHistory = "distance_history";

struct Built {
  std::unique_ptr<Settings> settings;  // what the graph's passes were built from
  BuiltFrame frame;
  graph::CompiledGraph compiled;

  const graph::ResourceDecl* resource(const std::string& name) const {
    for (const auto& r : frame.graph.resources())
      if (r.name == name) return &r;
    return nullptr;
  }
  bool allocated(const std::string& name) const {
    for (graph::ResourceId id = 0; id < frame.graph.resources().size(); ++id)
      if (frame.graph.resources()[id].name == name) return compiled.resources[id].used;
    return false;
  }
  bool runs(const std::string& pass) const {
    for (const auto& p : compiled.passes)
      if (frame.graph.passes()[p.pass].name == pass) return true;
    return false;
  }
  std::string culledReason(const std::string& pass) const {
    for (const auto& c : compiled.culled)
      if (frame.graph.passes()[c.pass].name == pass) return c.reason;
    return "";
  }
  uint64_t historyBytes() const {
    uint64_t bytes = 0;
    for (graph::ResourceId id = 0; id < frame.graph.resources().size(); ++id)
      if (frame.graph.resources()[id].kind == graph::ResourceKind::History && compiled.resources[id].used)
        bytes += graph::imageBytes(frame.graph.resources()[id].desc);
    return bytes;
  }
};

struct Case {
  int width = 320, height = 180;
  bool hasNormals = true;
  bool multiFrame = true;
  bool historyValid = true;
  GtaoSettings settings;
};

Built build(const Case& c, const HistoryStates& history = {}) {
  static VulkanContext noDevice;  // pipelines are only created when a pass executes
  static PipelineCache pipelines(noDevice);
  FrameCamera camera{glm::mat4(1.0f), glm::mat4(1.0f), c.width, c.height, 1};
  camera.projection[2][3] = -1.0f;
  camera.projection[3][3] = 0.0f;
  camera.projection[3][2] = -0.1f;
  Built b;
  b.settings = std::make_unique<Settings>(settingsOf(gtaoTechnique(), c.settings));
  FrameBuilder::Setup setup;
  setup.settings = b.settings.get();
  setup.camera = setup.previousCamera = camera;
  setup.capture = {c.hasNormals, false};
  setup.historyWanted = historyNeedsOf(*b.settings, c.multiFrame ? 2 : 1).keeps;
  setup.historyValid = setup.historyWanted && c.historyValid;
  setup.historyStates = history;
  b.frame = buildFrame(pipelines, setup, {});
  b.compiled = b.frame.graph.compile();
  graph::testing::checkCompiled(b.frame.graph, b.compiled);  // lifetimes, aliasing, every hazard covered by barriers
  return b;
}

TEST(AoGraph, DefaultMultiFrameReplayRunsTheThreePassesWithHistory) {
  auto b = build({});
  for (const char* pass : {"upload", "linearize_depth", "gtao", "spatial_columns", "spatial", "temporal", "readback"})
    EXPECT_TRUE(b.runs(pass)) << pass;
  EXPECT_GT(b.historyBytes(), 0u);
  EXPECT_TRUE(b.allocated("ao_history.previous"));
}

// The barrier the compiled graph puts before `pass` for `resource`, if any.
std::optional<graph::Barrier> barrierBefore(const Built& b, const std::string& pass, const std::string& resource) {
  for (const auto& p : b.compiled.passes) {
    if (b.frame.graph.passes()[p.pass].name != pass) continue;
    for (const auto& barrier : p.barriersBefore)
      if (b.frame.graph.resources()[barrier.resource].name == resource) return barrier;
  }
  return std::nullopt;
}

// What `aoreplay graph` shows for a second frame: its history images start where the first frame
// left them (the read-back's transfer read), not UNDEFINED, which would discard the history.
TEST(AoGraph, HistoryStatesAfterAFrameAreWhatItsHistoryImagesWereLeftIn) {
  Case first;
  first.historyValid = false;
  auto frame0 = build(first);
  auto after0 = historyStatesAfter(frame0.frame.graph, frame0.compiled);
  EXPECT_EQ(after0(kAoHistory, false).layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);  // read back last
  EXPECT_EQ(after0(kAoHistory, false).access, VK_ACCESS_2_TRANSFER_READ_BIT);
  EXPECT_EQ(after0(kDistanceHistory, false).layout, VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_EQ(after0(kAoHistory, true).layout, VK_IMAGE_LAYOUT_UNDEFINED) << "frame 1 writes a fresh image";

  auto frame1 = build({}, after0);
  auto toTemporal = barrierBefore(frame1, "temporal", "ao_history.previous");
  ASSERT_TRUE(toTemporal.has_value());
  EXPECT_EQ(toTemporal->before.layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  EXPECT_EQ(toTemporal->after.layout, VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_FALSE(barrierBefore(frame1, "temporal", "distance_history.previous").has_value())
      << "read after read in the same layout needs no barrier";
  EXPECT_EQ(barrierBefore(build({}), "temporal", "ao_history.previous")->before.layout, VK_IMAGE_LAYOUT_UNDEFINED)
      << "without the first frame's states the same barrier would discard the history";

  auto after1 = historyStatesAfter(frame1.frame.graph, frame1.compiled);
  EXPECT_EQ(after1(kAoHistory, true).layout, VK_IMAGE_LAYOUT_GENERAL) << "frame 2 writes what frame 1 read";
  EXPECT_EQ(after1(kAoHistory, false).layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
}

TEST(AoGraph, SingleFrameReplayHasNoTemporalPassAndNoHistoryMemory) {
  Case c;
  c.multiFrame = false;
  auto b = build(c);
  EXPECT_FALSE(b.runs("temporal"));
  EXPECT_NE(b.culledReason("temporal"), "");
  EXPECT_EQ(b.frame.notes.at("temporal"), "single-frame replay: no history");
  EXPECT_EQ(b.historyBytes(), 0u);
  for (const auto& r : b.frame.graph.resources()) EXPECT_NE(r.kind, graph::ResourceKind::History) << r.name;
  EXPECT_EQ(b.compiled.persistentBytes, 0u);
}

TEST(AoGraph, TemporalZeroDropsTheTemporalPassAndHistory) {
  Case c;
  c.settings.temporal = 0.0f;
  auto b = build(c);
  EXPECT_FALSE(b.runs("temporal"));
  EXPECT_EQ(b.frame.notes.at("temporal"), "temporal=0");
  EXPECT_EQ(b.historyBytes(), 0u);
}

TEST(AoGraph, NormalReconstructionOnlyWithoutCapturedNormals) {
  Case withNormals, depthOnly;
  depthOnly.hasNormals = false;
  auto a = build(withNormals), b = build(depthOnly);
  EXPECT_FALSE(a.runs("reconstruct_normals"));
  EXPECT_NE(a.culledReason("reconstruct_normals").find("normals_reconstructed"), std::string::npos);
  EXPECT_FALSE(a.allocated("normals_reconstructed"));
  EXPECT_TRUE(b.runs("reconstruct_normals"));
  EXPECT_TRUE(b.allocated("normals_reconstructed"));
  EXPECT_EQ(b.resource("normals"), nullptr) << "a depth-only capture uploads no normals";
}

TEST(AoGraph, SpatialPassOnlyWithSpatialOne) {
  Case c;
  c.settings.spatial = 0;
  auto b = build(c);
  EXPECT_FALSE(b.runs("spatial"));
  EXPECT_FALSE(b.runs("spatial_columns"));
  EXPECT_FALSE(b.allocated("ao_blurred"));
  EXPECT_FALSE(b.allocated("ao_column_sum"));
  EXPECT_FALSE(b.allocated("ao_column_weight_edge"));
  EXPECT_TRUE(b.runs("temporal"));
}

TEST(AoGraph, BentZeroUsesOneChannelAoImages) {
  Case c;
  c.settings.bent = 0;
  auto b = build(c);
  for (const char* name : {"ao_noisy", "ao_blurred", "ao_history.current"})
    EXPECT_EQ(b.resource(name)->desc.format, VK_FORMAT_R16_SFLOAT) << name;
  c.settings.bent = 1;
  auto withBent = build(c);
  EXPECT_EQ(withBent.resource("ao_noisy")->desc.format, VK_FORMAT_R16G16B16A16_SFLOAT);
}

// half_res=1 on an odd size: GTAO and the blur write 81x45 images for 161x89 pixels (texel t is
// pixel 2t, so the last row and column keep a texel); the temporal pass upsamples into the
// frame-sized history, and without one an `upsample` pass does.
TEST(AoGraph, HalfResolutionShrinksGtaoAndBlurImagesAndUpsamplesLast) {
  Case c;
  c.width = 161;
  c.height = 89;
  c.settings.halfRes = 1;
  auto b = build(c);
  for (const char* name : {"ao_noisy", "ao_column_sum", "ao_column_weight_edge", "ao_blurred"}) {
    EXPECT_EQ(b.resource(name)->desc.width, 81u) << name;
    EXPECT_EQ(b.resource(name)->desc.height, 45u) << name;
  }
  for (const char* name : {"ao_history.current", "ao_history.previous", "distance_history.current"}) {
    EXPECT_EQ(b.resource(name)->desc.width, 161u) << name;
    EXPECT_EQ(b.resource(name)->desc.height, 89u) << name;
  }
  EXPECT_TRUE(b.runs("temporal"));
  EXPECT_EQ(b.resource("ao_upsampled"), nullptr) << "the temporal pass upsamples; no pass of its own";

  c.multiFrame = false;
  auto single = build(c);
  EXPECT_FALSE(single.runs("temporal"));
  EXPECT_TRUE(single.runs("upsample"));
  ASSERT_NE(single.resource("ao_upsampled"), nullptr);
  EXPECT_EQ(single.resource("ao_upsampled")->desc.width, 161u);
  EXPECT_EQ(single.resource("ao_noisy")->desc.width, 81u);

  Case full = c;
  full.settings.halfRes = 0;
  auto fullSingle = build(full);
  EXPECT_FALSE(fullSingle.runs("upsample"));
  EXPECT_EQ(fullSingle.resource("ao_noisy")->desc.width, 161u);
}

TEST(AoGraph, HistoryIsAbsentWhenInvalid) {
  Case c;
  c.historyValid = false;
  auto b = build(c);
  EXPECT_EQ(b.resource("ao_history.previous"), nullptr);
  EXPECT_EQ(b.resource("distance_history.previous"), nullptr);
  EXPECT_TRUE(b.runs("temporal"));  // still writes this frame's history
}

TEST(AoGraph, PeakMemoryAt1080pFallsWithBentZeroAndWithAliasing) {
  Case c;
  c.width = 1920;
  c.height = 1080;
  auto bent = build(c);
  c.settings.bent = 0;
  auto noBent = build(c);
  auto mib = [](uint64_t b) { return double(b) / (1024.0 * 1024.0); };
  for (const auto* b : {&bent, &noBent}) {
    uint64_t unaliased = b->compiled.unaliasedTransientBytes + b->compiled.persistentBytes;
    EXPECT_LT(b->compiled.peakBytes(), unaliased);
    // History images never share memory.
    for (graph::ResourceId id = 0; id < b->frame.graph.resources().size(); ++id) {
      if (b->frame.graph.resources()[id].kind != graph::ResourceKind::Transient) {
        EXPECT_EQ(b->compiled.resources[id].memorySlot, -1);
      }
    }
  }
  EXPECT_LT(noBent.compiled.peakBytes(), bent.compiled.peakBytes());
  // The figures quoted in replay/techniques/gtao/README.md.
  std::printf("1920x1080 peak MiB: bent=1 %.2f (unaliased %.2f), bent=0 %.2f (unaliased %.2f)\n",
              mib(bent.compiled.peakBytes()), mib(bent.compiled.unaliasedTransientBytes + bent.compiled.persistentBytes),
              mib(noBent.compiled.peakBytes()),
              mib(noBent.compiled.unaliasedTransientBytes + noBent.compiled.persistentBytes));
}

}  // namespace
}  // namespace aor
