// XeGTAO's main pass (pass 2 of vaGTAO.cpp's Compute); the prefilter, denoiser, sky and
// screen-radius passes are shared blocks (shared_passes/horizon_blocks.h).
#include <algorithm>
#include <bit>
#include <cmath>

#include "shared_passes/shared_passes.h"
#include "shared_passes/camera.h"
#include "runtime/pass_context.h"
#include "techniques/xegtao/xegtao_settings.h"

namespace aor {
namespace {

constexpr uint32_t kMipTapsBytes = shader::kHorizonDepthMipLevels * sizeof(uint32_t);

// --debug mip_taps: a zeroed counter per level that the counting variant of the main pass adds to.
graph::ResourceId addMipTapsBuffer(FrameBuilder& frame) {
  auto taps = frame.graph().createBuffer("mip_taps", {kMipTapsBytes});
  frame.graph().addPass(
      "mip_taps_clear", [&](graph::PassBuilder& b) { b.write(taps, graph::Access::ClearWrite); },
      [taps](graph::PassContext& ctx) { vkCmdFillBuffer(ctx.cmd, ctx.buffer(taps).buffer, 0, kMipTapsBytes, 0); });
  return taps;
}

}  // namespace

XeGtaoWorking addXeGtaoMainPass(FrameBuilder& frame, const XeGtaoSettings& settings, graph::ResourceId depthMips) {
  glm::uvec2 size = frame.size();
  auto& g = frame.graph();
  XeGtaoWorking out;
  out.aoTerm = g.createImage("ao_term", {size.x, size.y, shared_passes::horizonTermFormat(settings.bent)});
  out.edges = g.createImage("edges", {size.x, size.y, VK_FORMAT_R8_UNORM});
  shader::HorizonConstants push = shared_passes::horizonConstants(frame.camera(), settings.blocks());
  bool countTaps = frame.wantsDebugView("mip_taps");
  graph::ResourceId taps = countTaps ? addMipTapsBuffer(frame) : graph::kNoResource;
  std::vector<SpecializationValue> specialization{
      specializationValue(shader::kXeGtaoSpecSlices, settings.slices), specializationValue(shader::kXeGtaoSpecSteps, settings.steps),
      specializationValue(shader::kHorizonSpecBent, settings.bent), specializationValue(shader::kXeGtaoSpecThin, settings.thinOccluderCompensation > 0.0f),
      specializationValue(shader::kHorizonSpecDepth32, settings.depth32),
      {uint32_t(shader::kXeGtaoSpecSampleDistributionPower), std::bit_cast<uint32_t>(settings.sampleDistributionPower)}};
  auto normals = frame.viewNormals();
  auto& pipelines = frame.pipelines();
  g.addPass(
      "xegtao_main",
      [&](graph::PassBuilder& b) {
        b.read(depthMips, graph::Access::SampledRead);
        b.read(normals, graph::Access::StorageRead);
        b.write(out.aoTerm);
        b.write(out.edges);
        if (countTaps) {  // atomic adds: a read and a write
          b.read(taps, graph::Access::StorageRead);
          b.write(taps, graph::Access::StorageWrite);
        }
      },
      [&pipelines, specialization, push, depthMips, normals, out, taps, countTaps, size](graph::PassContext& ctx) {
        if (countTaps) {
          dispatchCompute(ctx, pipelines.get("xegtao/main_pass_taps", specialization),
                          {depthMips, normals, out.aoTerm, out.edges, taps}, &push, size.x, size.y);
        } else {
          dispatchCompute(ctx, pipelines.get("xegtao/main_pass", specialization),
                          {depthMips, normals, out.aoTerm, out.edges}, &push, size.x, size.y);
        }
      });
  if (countTaps) frame.debugView("mip_taps", taps);
  return out;
}

}  // namespace aor
