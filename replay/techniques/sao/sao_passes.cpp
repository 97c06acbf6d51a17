// Seed 004's passes: camera-space Z of both layers, its rotated-grid pyramid, the SAO estimator
// and the separable bilateral blur (shaders/sao/).
#include <algorithm>
#include <bit>
#include <cmath>

#include "shared_passes/camera.h"
#include "blocks/linearize_depth.h"
#include "core/input_error.h"
#include "runtime/pass_context.h"
#include "techniques/sao/sao_settings.h"

namespace aor {
namespace {

constexpr float kGoldenRatioFraction = 0.61803398875f;

glm::uvec2 levelSize(glm::uvec2 size, uint32_t level) { return {std::max(1u, size.x >> level), std::max(1u, size.y >> level)}; }

}  // namespace

const char* const kSaoNoSecondLayer =
    "dual_layer=1 needs a second depth layer (a depth2 channel) and this capture has none; "
    "generate one with `aoreplay capture --depth2`, or use dual_layer=0 or auto";

bool saoUsesSecondLayer(const SaoSettings& s, const CaptureLayout& capture) {
  if (s.dualLayer == SaoDualLayer::On && !capture.depth2) throw InputError("", std::nullopt, "dual_layer", kSaoNoSecondLayer);
  return s.dualLayer == SaoDualLayer::On || (s.dualLayer == SaoDualLayer::Auto && capture.depth2);
}

VkFormat saoCszFormat(bool csz32, bool dualLayer) {
  if (csz32) return dualLayer ? VK_FORMAT_R32G32_SFLOAT : VK_FORMAT_R32_SFLOAT;
  return dualLayer ? VK_FORMAT_R16G16_SFLOAT : VK_FORMAT_R16_SFLOAT;
}

uint32_t saoMipLevels(uint32_t width, uint32_t height) {
  uint32_t available = uint32_t(std::bit_width(std::max(width, height)));  // floor(log2) + 1
  return std::min(shader::kSaoMipLevels, available);
}

graph::ResourceId addSaoCszPass(FrameBuilder& frame, const SaoSettings& s, bool dualLayer) {
  const auto& cam = frame.camera();
  auto params = projectionParams(cam.projection, cam.width, cam.height);
  shader::SaoCszConstants c{};
  c.size = {cam.width, cam.height};
  c.projection22 = params.projection22;
  c.projection32 = params.projection32;
  c.reversedDepth = params.reversedDepth ? 1u : 0u;
  c.maxDistance = s.csz32 ? shader::kMaxViewDistance : shader::kSaoMaxHalfDistance;
  auto size = frame.size();
  auto csz = frame.graph().createImage("csz", {size.x, size.y, saoCszFormat(s.csz32, dualLayer), saoMipLevels(size.x, size.y)});
  graph::ResourceId depth = frame.depth(), depth2 = frame.depth2();
  auto& pipelines = frame.pipelines();
  frame.graph().addPass(
      "csz",
      [&](graph::PassBuilder& b) {
        b.read(depth, graph::Access::StorageRead);
        if (dualLayer) b.read(depth2, graph::Access::StorageRead);
        b.write(csz, graph::Access::StorageWrite, graph::Subresources::mip(0));
      },
      [&pipelines, c, depth, depth2, csz, dualLayer](graph::PassContext& ctx) {
        graph::Subresources level0 = graph::Subresources::mip(0);
        if (dualLayer)
          dispatchCompute(ctx, pipelines.get("sao/csz_dual"), {depth, depth2, Bind(csz, level0)}, &c, uint32_t(c.size.x),
                          uint32_t(c.size.y));
        else
          dispatchCompute(ctx, pipelines.get("sao/csz_single"), {depth, Bind(csz, level0)}, &c, uint32_t(c.size.x),
                          uint32_t(c.size.y));
      });
  return csz;
}

void addSaoMinifyPasses(FrameBuilder& frame, graph::ResourceId csz) {
  uint32_t levels = frame.graph().resources()[csz].desc.mipLevels;
  auto& pipelines = frame.pipelines();
  for (uint32_t level = 1; level < levels; ++level) {
    glm::uvec2 size = levelSize(frame.size(), level), source = levelSize(frame.size(), level - 1);
    shader::SaoMinifyConstants c{};
    c.size = glm::ivec2(size);
    c.sourceSize = glm::ivec2(source);
    frame.graph().addPass(
        "csz_mip" + std::to_string(level),
        [&](graph::PassBuilder& b) {
          b.read(csz, graph::Access::SampledRead, graph::Subresources::mip(level - 1));
          b.write(csz, graph::Access::StorageWrite, graph::Subresources::mip(level));
        },
        [&pipelines, c, csz, level](graph::PassContext& ctx) {
          dispatchCompute(ctx, pipelines.get("sao/minify"),
                          {Bind(csz, graph::Subresources::mip(level - 1)), Bind(csz, graph::Subresources::mip(level))}, &c,
                          uint32_t(c.size.x), uint32_t(c.size.y));
        });
  }
}

graph::ResourceId addSaoPass(FrameBuilder& frame, const SaoSettings& s, bool dualLayer, graph::ResourceId csz) {
  const auto& cam = frame.camera();
  auto params = projectionParams(cam.projection, cam.width, cam.height);
  shader::SaoConstants c{};
  c.worldToView0 = glm::vec4(glm::vec3(cam.view[0]), 0.0f);
  c.worldToView1 = glm::vec4(glm::vec3(cam.view[1]), 0.0f);
  c.worldToView2 = glm::vec4(glm::vec3(cam.view[2]), 0.0f);
  c.ndcToViewMul = params.ndcToViewMul;
  c.ndcToViewAdd = params.ndcToViewAdd;
  c.invSize = {1.0f / float(cam.width), 1.0f / float(cam.height)};
  c.size = {cam.width, cam.height};
  c.radius = s.radius;
  c.invRadius2 = 1.0f / (s.radius * s.radius);
  c.bias = s.bias;
  c.intensityFactor = shader::kSaoNormalisation * s.intensity / float(s.samples);
  c.projScale = params.pixelsPerUnit;
  c.spiralTurns = float(s.spiralTurns);
  // A still spiral unless temporal accumulation can average rotations across frames.
  c.rotationOffset = s.temporal > 0.0f ? float(cam.frameIndex % 64u) * kGoldenRatioFraction * 2.0f * shader::kPi : 0.0f;
  c.maxMip = int(frame.graph().resources()[csz].desc.mipLevels) - 1;
  auto size = frame.size();
  auto ao = frame.graph().createImage("ao_raw", {size.x, size.y, VK_FORMAT_R16_SFLOAT});
  // The capture's normals are rotated in the pass itself (no view_normals image); without them,
  // the front's reconstructed ones, already in view space.
  bool worldNormals = frame.worldNormals() != graph::kNoResource;
  graph::ResourceId normals = worldNormals ? frame.worldNormals() : frame.reconstructedNormals();
  std::vector<SpecializationValue> specialization{{uint32_t(shader::kSaoSpecSamples), uint32_t(s.samples)},
                                                  {uint32_t(shader::kSaoSpecDualLayer), dualLayer ? 1u : 0u},
                                                  {uint32_t(shader::kSaoSpecWorldNormals), worldNormals ? 1u : 0u}};
  auto& pipelines = frame.pipelines();
  frame.graph().addPass(
      "sao",
      [&](graph::PassBuilder& b) {
        b.read(csz, graph::Access::SampledRead);
        b.read(normals, graph::Access::StorageRead);
        b.write(ao);
      },
      [&pipelines, specialization, c, csz, normals, ao](graph::PassContext& ctx) {
        dispatchCompute(ctx, pipelines.get("sao/sao", specialization), {csz, normals, ao}, &c, uint32_t(c.size.x),
                        uint32_t(c.size.y));
      });
  return ao;
}

graph::ResourceId addSaoBlurPass(FrameBuilder& frame, const SaoSettings& s, graph::ResourceId ao, graph::ResourceId csz,
                                 bool horizontal) {
  shader::SaoBlurConstants c{};
  c.size = glm::ivec2(frame.size());
  c.axis = horizontal ? glm::ivec2(1, 0) : glm::ivec2(0, 1);
  c.radius = s.blurRadius;
  c.step = s.blurStep;
  c.sigma = std::max(1.0f, float(s.blurRadius) * 0.5f);  // the paper's weights for radius 4 have sigma 2
  c.edgeSharpness = s.edgeSharpness;
  auto size = frame.size();
  const char* name = horizontal ? "ao_blur_h" : "ao_blur";
  auto out = frame.graph().createImage(name, {size.x, size.y, VK_FORMAT_R16_SFLOAT});
  auto& pipelines = frame.pipelines();
  frame.graph().addPass(
      horizontal ? "blur_h" : "blur_v",
      [&](graph::PassBuilder& b) {
        b.read(ao, graph::Access::StorageRead);
        b.read(csz, graph::Access::SampledRead, graph::Subresources::mip(0));
        b.write(out);
      },
      [&pipelines, c, ao, csz, out](graph::PassContext& ctx) {
        dispatchCompute(ctx, pipelines.get("sao/blur"), {ao, Bind(csz, graph::Subresources::mip(0)), out}, &c,
                        uint32_t(c.size.x), uint32_t(c.size.y));
      });
  return out;
}

}  // namespace aor
