// The counting build (vk/op_counter.h, shaders/counting/count_ops.glsl) counts what a pass's shader
// really executed. Its counts are held to figures known without the GPU: one load and one store
// per pixel for the depth linearisation, and for GTAO the number of load calls its own per-pixel
// code makes when the CPU mirror runs it (sky pixels stop early, degenerate slices skip their
// steps, so the count is data dependent and only the shader's own code can predict it).
#include <gtest/gtest.h>

#include <algorithm>

#include "cpu/gtao_cpu.h"
#include "gpu_test_support.h"
#include "vk/op_counter.h"

namespace aor::test {
namespace {

// The per-pass counts of the last replayed frame of `capture`, replayed through the counting build.
std::vector<DispatchCounts> countedReplay(const std::filesystem::path& capture, const GtaoSettings& settings,
                                          int begin, int end) {
  VulkanContext& vk = validatedContext();
  OpCounter counter(vk);
  struct Counting {
    VulkanContext& vk;
    ~Counting() { vk.opCounter = nullptr; }
  } counting{vk};
  vk.opCounter = &counter;
  auto replayed = replay(capture, settings, begin, end);
  std::vector<std::string> passes;
  for (const auto& pass : replayed.result.frames.back().passes) passes.push_back(pass.name);
  return lastFramePerPass(counter.dispatches(), passes);
}

const DispatchCounts& passNamed(const std::vector<DispatchCounts>& counts, const std::string& name) {
  auto found = std::find_if(counts.begin(), counts.end(), [&](const DispatchCounts& c) { return c.pass == name; });
  if (found == counts.end()) throw std::runtime_error("no counts for pass " + name);
  return *found;
}

TEST(OpCounts, DepthLinearisationLoadsAndStoresEachPixelOnce) {
  auto capture = generatedCapture("boxes", "orbit", 80, 45, 2);
  auto counts = countedReplay(capture, GtaoSettings{}, 1, 2);
  const auto& linearize = passNamed(counts, "linearize_depth");
  EXPECT_EQ(linearize.op(OpKind::ImageLoad), 80u * 45u);
  EXPECT_EQ(linearize.op(OpKind::ImageStore), 80u * 45u);
  EXPECT_EQ(linearize.op(OpKind::Fetch) + linearize.op(OpKind::Sample) + linearize.op(OpKind::Gather), 0u);
  EXPECT_GE(linearize.invocations, 80u * 45u);  // whole workgroups: the edge threads return early
  EXPECT_EQ(linearize.dispatches, 1u);
  // Bytes are per bound subresource: R32F distance written, the capture's depth read.
  EXPECT_EQ(linearize.bytesWritten, 80u * 45u * 4u);
}

TEST(OpCounts, GtaoLoadsEqualTheLoadCallsOfItsOwnCodeOnTheCpu) {
  auto capturePath = generatedCapture("boxes", "orbit", 80, 45, 2);
  Capture capture = loadCapture(capturePath);
  const auto& frame = capture.frames[1];
  FrameCamera camera{frame.view, frame.projection, capture.width, capture.height, 1};
  uint64_t previous = 0;
  for (auto [slices, steps] : {std::pair{2, 2}, std::pair{3, 3}, std::pair{6, 8}}) {
    GtaoSettings settings = gtaoOnly();
    settings.slices = slices;
    settings.steps = steps;
    uint64_t cpuLoads = 0;
    gtaoOnCpu(loadGBuffer(capture, 1), camera, settings, &cpuLoads);
    const auto& gtao = passNamed(countedReplay(capturePath, settings, 1, 2), "gtao");
    EXPECT_EQ(gtao.op(OpKind::ImageLoad), cpuLoads) << slices << "x" << steps;
    EXPECT_EQ(gtao.op(OpKind::ImageStore), 80u * 45u) << slices << "x" << steps;
    // Two loads per pixel for the centre and two per step and slice at most: far more than the
    // centre alone, since the boxes' scene has little sky.
    uint64_t pixels = 80u * 45u;
    EXPECT_LE(gtao.op(OpKind::ImageLoad), pixels * (2 + 2 * uint64_t(slices * steps)));
    EXPECT_GT(gtao.op(OpKind::ImageLoad), pixels * (2 + uint64_t(slices * steps)));
    EXPECT_GT(gtao.op(OpKind::ImageLoad), previous);
    previous = gtao.op(OpKind::ImageLoad);
  }
}

}  // namespace
}  // namespace aor::test
