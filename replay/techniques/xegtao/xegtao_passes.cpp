// XeGTAO's three passes (vaGTAO.cpp's Compute, in this tool's render graph): prefilter, main pass,
// denoise_passes x denoise; then the sky pass (the engine's part) and the screen-radius debug pass.
#include <algorithm>
#include <bit>
#include <cmath>

#include "shared_passes/shared_passes.h"
#include "shared_passes/camera.h"
#include "runtime/pass_context.h"
#include "techniques/xegtao/xegtao_settings.h"

namespace aor {
namespace {

constexpr uint32_t kMipTapsBytes = shader::kXeGtaoDepthMipLevels * sizeof(uint32_t);

// Levels of the depth chain: XeGTAO's five, fewer where the frame is too small for them.
uint32_t depthMipLevels(glm::uvec2 size) {
  uint32_t levels = 1;
  while (levels < uint32_t(shader::kXeGtaoDepthMipLevels) && (std::max(size.x, size.y) >> levels) > 0) ++levels;
  return levels;
}

struct PrefilterPush {
  shader::XeGtaoConstants c;
  int32_t mipLevels;
};

VkFormat aoTermFormat(bool bent) { return bent ? VK_FORMAT_R32_UINT : VK_FORMAT_R8_UINT; }

// --debug mip_taps: a zeroed counter per level that the counting variant of the main pass adds to.
graph::ResourceId addMipTapsBuffer(FrameBuilder& frame) {
  auto taps = frame.graph().createBuffer("mip_taps", {kMipTapsBytes});
  frame.graph().addPass(
      "mip_taps_clear", [&](graph::PassBuilder& b) { b.write(taps, graph::Access::ClearWrite); },
      [taps](graph::PassContext& ctx) { vkCmdFillBuffer(ctx.cmd, ctx.buffer(taps).buffer, 0, kMipTapsBytes, 0); });
  return taps;
}

}  // namespace

shader::XeGtaoConstants xegtaoConstants(const FrameCamera& camera, const XeGtaoSettings& settings) {
  auto params = projectionParams(camera.projection, camera.width, camera.height);
  shader::XeGtaoConstants c{};
  c.viewportSize = {camera.width, camera.height};
  c.viewportPixelSize = {1.0f / float(camera.width), 1.0f / float(camera.height)};
  ForwardViewCamera forward = forwardViewCamera(params);  // XeGTAO's view space and uv
  c.depthUnpackConsts = forward.depthUnpack;
  c.cameraTanHalfFov = forward.tanHalfFov;
  c.viewAxisSigns = forward.axisSigns;
  c.ndcToViewMul = forward.ndcToViewMul;
  c.ndcToViewAdd = forward.ndcToViewAdd;
  c.ndcToViewMulXPixelSize = c.ndcToViewMul * c.viewportPixelSize;
  c.effectRadius = settings.radius;
  c.effectFalloffRange = settings.falloffRange;
  c.radiusMultiplier = settings.radiusMultiplier;
  c.padding0 = 0.0f;
  c.finalValuePower = settings.finalValuePower;
  c.denoiseBlurBeta = shader::kXeGtaoDenoiseBlurBeta;  // denoise_passes >= 1: XeGTAO's 1e4 (off) never applies
  c.sampleDistributionPower = settings.sampleDistributionPower;
  c.thinOccluderCompensation = settings.thinOccluderCompensation;
  c.depthMipSamplingOffset = settings.depthMipSamplingOffset;
  c.noiseIndex = int(camera.frameIndex % shader::kXeGtaoNoisePeriod);
  return c;
}

graph::ResourceId addXeGtaoPrefilter(FrameBuilder& frame, const XeGtaoSettings& settings) {
  glm::uvec2 size = frame.size();
  uint32_t levels = depthMipLevels(size);
  VkFormat format = settings.depth32 ? VK_FORMAT_R32_SFLOAT : VK_FORMAT_R16_SFLOAT;
  auto mips = frame.graph().createImage("depth_mips", {size.x, size.y, format, levels});
  PrefilterPush push{xegtaoConstants(frame.camera(), settings), int32_t(levels)};
  auto depth = frame.depth();
  auto& pipelines = frame.pipelines();
  frame.graph().addPass(
      "xegtao_prefilter",
      [&](graph::PassBuilder& b) {
        b.read(depth, graph::Access::SampledRead);
        b.write(mips);
      },
      [&pipelines, push, depth, mips, levels, size](graph::PassContext& ctx) {
        auto level = [&](uint32_t k) { return graph::Subresources::mip(std::min(k, levels - 1)); };
        dispatchCompute(ctx, pipelines.get("xegtao/prefilter_depths"),
                        {depth, {mips, level(0)}, {mips, level(1)}, {mips, level(2)}, {mips, level(3)}, {mips, level(4)}},
                        &push, (size.x + 1) / 2, (size.y + 1) / 2);
      });
  return mips;
}

XeGtaoWorking addXeGtaoMainPass(FrameBuilder& frame, const XeGtaoSettings& settings, graph::ResourceId depthMips) {
  glm::uvec2 size = frame.size();
  auto& g = frame.graph();
  XeGtaoWorking out;
  out.aoTerm = g.createImage("ao_term", {size.x, size.y, aoTermFormat(settings.bent)});
  out.edges = g.createImage("edges", {size.x, size.y, VK_FORMAT_R8_UNORM});
  shader::XeGtaoConstants push = xegtaoConstants(frame.camera(), settings);
  bool countTaps = frame.wantsDebugView("mip_taps");
  graph::ResourceId taps = countTaps ? addMipTapsBuffer(frame) : graph::kNoResource;
  std::vector<SpecializationValue> specialization{
      specializationValue(shader::kXeGtaoSpecSlices, settings.slices), specializationValue(shader::kXeGtaoSpecSteps, settings.steps),
      specializationValue(shader::kXeGtaoSpecBent, settings.bent), specializationValue(shader::kXeGtaoSpecThin, settings.thinOccluderCompensation > 0.0f),
      specializationValue(shader::kXeGtaoSpecDepth32, settings.depth32),
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

graph::ResourceId addXeGtaoDenoise(FrameBuilder& frame, const XeGtaoSettings& settings, const XeGtaoWorking& working) {
  glm::uvec2 size = frame.size();
  auto& g = frame.graph();
  auto constants = xegtaoConstants(frame.camera(), settings);
  std::vector<SpecializationValue> specialization{specializationValue(shader::kXeGtaoSpecBent, settings.bent)};
  auto& pipelines = frame.pipelines();
  graph::ResourceId source = working.aoTerm;
  int passes = std::max(1, settings.denoisePasses);
  for (int i = 0; i < passes; ++i) {
    bool last = i == passes - 1;
    // Passes before the last keep XeGTAO's working format (its ping-pong pair, as transients).
    graph::ResourceId target =
        last ? g.createImage("ao_denoised", {size.x, size.y, shared_passes::aoImageFormat(settings.bent)})
             : g.createImage("ao_term_" + std::to_string(i + 1), {size.x, size.y, aoTermFormat(settings.bent)});
    std::string shader = last ? "xegtao/denoise_last" : "xegtao/denoise";
    auto edges = working.edges;
    g.addPass(
        last ? "xegtao_denoise" : "xegtao_denoise_" + std::to_string(i + 1),
        [&](graph::PassBuilder& b) {
          b.read(source, graph::Access::SampledRead);
          b.read(edges, graph::Access::SampledRead);
          b.write(target);
        },
        [&pipelines, shader, specialization, constants, source, edges, target, size](graph::PassContext& ctx) {
          dispatchCompute(ctx, pipelines.get(shader, specialization), {source, edges, target}, &constants,
                          (size.x + 1) / 2, size.y);
        });
    source = target;
  }
  return source;
}

void addXeGtaoSky(FrameBuilder& frame, const XeGtaoSettings& settings, graph::ResourceId denoised) {
  glm::uvec2 size = frame.size();
  auto constants = xegtaoConstants(frame.camera(), settings);
  auto params = projectionParams(frame.camera().projection, frame.camera().width, frame.camera().height);
  std::vector<SpecializationValue> specialization{specializationValue(shader::kXeGtaoSpecBent, settings.bent),
                                                  specializationValue(shader::kXeGtaoSpecReversedDepth, params.reversedDepth)};
  auto depth = frame.depth();
  auto& pipelines = frame.pipelines();
  frame.graph().addPass(
      "xegtao_sky",
      [&](graph::PassBuilder& b) {
        b.read(depth, graph::Access::SampledRead);
        b.read(denoised, graph::Access::StorageRead);  // in place: only the sky pixels change
        b.write(denoised);
      },
      [&pipelines, specialization, constants, depth, denoised, size](graph::PassContext& ctx) {
        dispatchCompute(ctx, pipelines.get("xegtao/sky", specialization), {depth, denoised}, &constants, (size.x + 1) / 2,
                        (size.y + 1) / 2);
      });
}

graph::ResourceId addXeGtaoScreenRadius(FrameBuilder& frame, const XeGtaoSettings& settings, graph::ResourceId depthMips) {
  glm::uvec2 size = frame.size();
  auto radius = frame.graph().createImage("screen_radius", {size.x, size.y, VK_FORMAT_R32_SFLOAT});
  auto constants = xegtaoConstants(frame.camera(), settings);
  std::vector<SpecializationValue> specialization{specializationValue(shader::kXeGtaoSpecDepth32, settings.depth32)};
  auto& pipelines = frame.pipelines();
  frame.graph().addPass(
      "xegtao_screen_radius",
      [&](graph::PassBuilder& b) {
        b.read(depthMips, graph::Access::SampledRead, graph::Subresources::mip(0));
        b.write(radius);
      },
      [&pipelines, specialization, constants, depthMips, radius, size](graph::PassContext& ctx) {
        dispatchCompute(ctx, pipelines.get("xegtao/screen_radius", specialization),
                        {{depthMips, graph::Subresources::mip(0)}, radius}, &constants, size.x, size.y);
      });
  return radius;
}

}  // namespace aor
