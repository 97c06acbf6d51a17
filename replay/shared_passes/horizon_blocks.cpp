// XeGTAO's passes other than its main pass (vaGTAO.cpp's Compute, in this tool's render graph):
// the depth prefilter, denoise_passes x denoise, and the sky and screen-radius passes; shared by
// the horizon-search techniques.
#include "shared_passes/horizon_blocks.h"

#include <algorithm>

#include <fmt/format.h>

#include "shared_passes/camera.h"
#include "shared_passes/shared_passes.h"
#include "runtime/pass_context.h"

namespace aor::shared_passes {
namespace {

constexpr float kHardEdgeFalloffRange = 1e-4f;

// Levels of the depth chain: XeGTAO's five, fewer where the frame is too small for them.
uint32_t depthMipLevels(glm::uvec2 size) {
  uint32_t levels = 1;
  while (levels < uint32_t(shader::kHorizonDepthMipLevels) && (std::max(size.x, size.y) >> levels) > 0) ++levels;
  return levels;
}

struct PrefilterPush {
  shader::HorizonConstants c;
  int32_t mipLevels;
};

}  // namespace

VkFormat horizonTermFormat(bool bent) { return bent ? VK_FORMAT_R32_UINT : VK_FORMAT_R8_UINT; }

shader::HorizonConstants horizonConstants(const FrameCamera& camera, const HorizonBlockSettings& settings) {
  auto params = projectionParams(camera.projection, camera.width, camera.height);
  shader::HorizonConstants c{};
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
  // 0 is a hard edge at the radius: XeGTAO's weight divides by the range (0/0 there), so the
  // passes get a range too short to matter instead; any range from 1e-4 up is kept as given.
  c.effectFalloffRange = std::max(settings.falloffRange, kHardEdgeFalloffRange);
  c.radiusMultiplier = settings.radiusMultiplier;
  c.padding0 = 0.0f;
  c.finalValuePower = settings.finalValuePower;
  c.denoiseBlurBeta = shader::kHorizonDenoiseBlurBeta;  // denoise_passes >= 1: XeGTAO's 1e4 (off) never applies
  c.sampleDistributionPower = settings.sampleDistributionPower;
  c.thinOccluderCompensation = settings.thinOccluderCompensation;
  c.depthMipSamplingOffset = settings.depthMipSamplingOffset;
  c.noiseIndex = int(camera.frameIndex % shader::kHorizonNoisePeriod);
  return c;
}

graph::ResourceId addHorizonDepthMips(FrameBuilder& frame, const HorizonBlockSettings& settings, const std::string& passName) {
  glm::uvec2 size = frame.size();
  uint32_t levels = depthMipLevels(size);
  VkFormat format = settings.depth32 ? VK_FORMAT_R32_SFLOAT : VK_FORMAT_R16_SFLOAT;
  auto mips = frame.graph().createImage("depth_mips", {size.x, size.y, format, levels});
  PrefilterPush push{horizonConstants(frame.camera(), settings), int32_t(levels)};
  auto depth = frame.depth();
  auto& pipelines = frame.pipelines();
  frame.graph().addPass(
      passName,
      [&](graph::PassBuilder& b) {
        b.read(depth, graph::Access::SampledRead);
        b.write(mips);
      },
      [&pipelines, push, depth, mips, levels, size](graph::PassContext& ctx) {
        auto level = [&](uint32_t k) { return graph::Subresources::mip(std::min(k, levels - 1)); };
        dispatchCompute(ctx, pipelines.get("horizon/prefilter_depths"),
                        {depth, {mips, level(0)}, {mips, level(1)}, {mips, level(2)}, {mips, level(3)}, {mips, level(4)}},
                        &push, (size.x + 1) / 2, (size.y + 1) / 2);
      });
  return mips;
}

graph::ResourceId addHorizonDenoise(FrameBuilder& frame, const HorizonBlockSettings& settings, const HorizonWorking& working,
                                    const std::string& passName) {
  glm::uvec2 size = frame.size();
  auto& g = frame.graph();
  auto constants = horizonConstants(frame.camera(), settings);
  std::vector<SpecializationValue> specialization{specializationValue(shader::kHorizonSpecBent, settings.bent)};
  auto& pipelines = frame.pipelines();
  graph::ResourceId source = working.aoTerm;
  int passes = std::max(1, settings.denoisePasses);
  for (int i = 0; i < passes; ++i) {
    bool last = i == passes - 1;
    // Passes before the last keep XeGTAO's working format (its ping-pong pair, as transients).
    graph::ResourceId target =
        last ? g.createImage("ao_denoised", {size.x, size.y, aoImageFormat(settings.bent)})
             : g.createImage("ao_term_" + std::to_string(i + 1), {size.x, size.y, horizonTermFormat(settings.bent)});
    std::string shader = last ? "horizon/denoise_last" : "horizon/denoise";
    auto edges = working.edges;
    g.addPass(
        last ? passName : passName + "_" + std::to_string(i + 1),
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

void addHorizonSky(FrameBuilder& frame, const HorizonBlockSettings& settings, graph::ResourceId denoised,
                   const std::string& passName) {
  glm::uvec2 size = frame.size();
  auto constants = horizonConstants(frame.camera(), settings);
  auto params = projectionParams(frame.camera().projection, frame.camera().width, frame.camera().height);
  std::vector<SpecializationValue> specialization{specializationValue(shader::kHorizonSpecBent, settings.bent),
                                                  specializationValue(shader::kHorizonSpecReversedDepth, params.reversedDepth)};
  auto depth = frame.depth();
  auto& pipelines = frame.pipelines();
  frame.graph().addPass(
      passName,
      [&](graph::PassBuilder& b) {
        b.read(depth, graph::Access::SampledRead);
        b.read(denoised, graph::Access::StorageRead);  // in place: only the sky pixels change
        b.write(denoised);
      },
      [&pipelines, specialization, constants, depth, denoised, size](graph::PassContext& ctx) {
        dispatchCompute(ctx, pipelines.get("horizon/sky", specialization), {depth, denoised}, &constants, (size.x + 1) / 2,
                        (size.y + 1) / 2);
      });
}

graph::ResourceId addHorizonScreenRadius(FrameBuilder& frame, const HorizonBlockSettings& settings, graph::ResourceId depthMips,
                                         const std::string& passName) {
  glm::uvec2 size = frame.size();
  auto radius = frame.graph().createImage("screen_radius", {size.x, size.y, VK_FORMAT_R32_SFLOAT});
  auto constants = horizonConstants(frame.camera(), settings);
  std::vector<SpecializationValue> specialization{specializationValue(shader::kHorizonSpecDepth32, settings.depth32)};
  auto& pipelines = frame.pipelines();
  frame.graph().addPass(
      passName,
      [&](graph::PassBuilder& b) {
        b.read(depthMips, graph::Access::SampledRead, graph::Subresources::mip(0));
        b.write(radius);
      },
      [&pipelines, specialization, constants, depthMips, radius, size](graph::PassContext& ctx) {
        dispatchCompute(ctx, pipelines.get("horizon/screen_radius", specialization),
                        {{depthMips, graph::Subresources::mip(0)}, radius}, &constants, size.x, size.y);
      });
  return radius;
}

void addHorizonDepthViews(FrameBuilder& frame, graph::ResourceId depthMips) {
  frame.debugView("linear_depth", depthMips, {0, 1, 0, 1});
  uint32_t levels = frame.graph().resources().at(depthMips).desc.mipLevels;
  for (uint32_t k = 1; k < levels; ++k) frame.debugView(fmt::format("depth_mip{}", k), depthMips, {k, 1, 0, 1});
}

std::vector<DebugView> horizonDebugViews() {
  return {
      {"linear_depth", "the depth chain's MIP 0: XeGTAO's view z (R16F, R32F with depth32=1; sky at its far value)"},
      {"depth_mip1", "depth MIP 1 (weighted-average filter)"},
      {"depth_mip2", "depth MIP 2"},
      {"depth_mip3", "depth MIP 3"},
      {"depth_mip4", "depth MIP 4"},
      {"view_normals", "the normals the main pass reads (the shared front's, this tool's view space)"},
      {"screen_radius", "the main pass's screen-space radius, pixels (R32F)"},
      {"edges", "packed edges for the denoiser (R8_UNORM: 2 bits a side, left in the top bits)"},
  };
}

}  // namespace aor::shared_passes
