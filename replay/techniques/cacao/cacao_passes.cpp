// FidelityFX CACAO's passes (ffx_cacao_impl.cpp's FFX_CACAO_VkDraw, in this tool's render graph),
// in the seed's order, each present only in the configurations the seed's table lists: clear load
// counter, prepare depths, prepare normals, [highest: Q3 base, importance map, postprocess A, B],
// generate, edge-sensitive blur, apply or bilateral upsample. Every pass over the deinterleaved
// layers is one dispatch with a workgroup layer per layer (FidelityFX: one dispatch per layer).
#include <algorithm>

#include "runtime/pass_context.h"
#include "techniques/cacao/cacao_settings.h"

namespace aor {
namespace {

using graph::Access;
using graph::ResourceId;
using graph::Subresources;

constexpr uint32_t kAdaptiveTapCounters = 4;  // extra taps, pixels where importance >= 0.5; then below

// The deinterleaved depth's MIP chain: FidelityFX's four levels, fewer where a layer is too small.
uint32_t cacaoDepthMipLevels(glm::uvec2 size) {
  uint32_t levels = 1;
  while (levels < shader::kCacaoDepthMips && (std::max(size.x, size.y) >> levels) > 0) ++levels;
  return levels;
}

// What every pass of one frame shares: the sizes, the constants buffer, the layers dispatched.
struct CacaoFrame {
  FrameBuilder& frame;
  const CacaoSettings& settings;
  CacaoBufferSizes sizes;
  bool generateNormals = false;
  uint32_t layers = 4;  // layers dispatched: 2 at lowest (0 and 3)
  ResourceId constants = graph::kNoResource, loadCounter = graph::kNoResource;

  graph::RenderGraph& g() { return frame.graph(); }
  PipelineCache& pipelines() { return frame.pipelines(); }
  ResourceId layerImage(const std::string& name, glm::uvec2 size, VkFormat format, uint32_t mips = 1) {
    return g().createImage(name, {size.x, size.y, format, mips, uint32_t(shader::kCacaoLayers)});
  }
};

// FFX_CACAO_ClearLoadCounter, with the frame's four constant buffers written by vkCmdUpdateBuffer
// (recorded into the frame's command buffer, so frames in flight never share them).
void addClearLoadCounter(CacaoFrame& f) {
  auto constants = cacaoConstants(f.frame.camera(), f.settings);
  f.constants = f.g().createBuffer("cacao_constants", {sizeof(constants)});
  f.loadCounter = f.g().createBuffer("cacao_load_counter", {sizeof(uint32_t)});
  ResourceId buffer = f.constants, counter = f.loadCounter;
  f.g().addPass(
      "cacao_clear_load_counter",
      [&](graph::PassBuilder& b) {
        b.write(buffer, Access::ClearWrite);
        b.writeIfRead(counter, Access::ClearWrite);  // read at highest only
      },
      [constants, buffer, counter](graph::PassContext& ctx) {
        vkCmdUpdateBuffer(ctx.cmd, ctx.buffer(buffer).buffer, 0, sizeof(constants), constants.data());
        if (ctx.has(counter)) vkCmdFillBuffer(ctx.cmd, ctx.buffer(counter).buffer, 0, sizeof(uint32_t), 0);
      });
}

// FFX_CACAO_Prepare{Native,Downsampled}Depths[Half|AndMips]: the view depth of each 2x2 phase in
// its own layer, with MIPs 1-3 from medium.
ResourceId addPrepareDepths(CacaoFrame& f) {
  bool mips = cacaoDepthMips(f.settings.quality);
  glm::uvec2 size = f.sizes.deinterleavedDepth;
  uint32_t levels = mips ? cacaoDepthMipLevels(size) : 1u;
  ResourceId depths = f.layerImage("cacao_deinterleaved_depths", size, VK_FORMAT_R16_SFLOAT, levels);
  std::vector<SpecializationValue> specialization{specializationValue(shader::kCacaoSpecDownsampled, f.settings.downsample),
                                                  specializationValue(shader::kCacaoSpecHalf, cacaoTwoLayers(f.settings.quality)),
                                                  specializationValue(shader::kCacaoSpecDepthMipLevels, int(levels))};
  ResourceId constants = f.constants, depth = f.frame.depth();
  auto& pipelines = f.pipelines();
  f.g().addPass(
      cacaoPrepareDepthsPassName(f.settings),
      [&](graph::PassBuilder& b) {
        b.read(constants, Access::UniformRead);
        b.read(depth, Access::SampledRead);
        b.write(depths);
      },
      [&pipelines, specialization, constants, depth, depths, mips, levels, size](graph::PassContext& ctx) {
        if (mips) {
          // A frame too small for four levels binds its last level in the place of the missing ones.
          auto level = [&](uint32_t k) { return Bind(depths, Subresources::mip(std::min(k, levels - 1))); };
          dispatchCompute(ctx, pipelines.get("cacao/prepare_depths_and_mips", specialization),
                          {constants, depth, level(0), level(1), level(2), level(3)}, nullptr, size.x, size.y);
        } else {
          dispatchCompute(ctx, pipelines.get("cacao/prepare_depths", specialization), {constants, depth, depths}, nullptr,
                          size.x, size.y);
        }
      });
  return depths;
}

// FFX_CACAO_Prepare{Native,Downsampled}Normals (from depth) or ..NormalsFromInputNormals.
ResourceId addPrepareNormals(CacaoFrame& f) {
  ResourceId normals = f.layerImage("cacao_deinterleaved_normals", f.sizes.ssao, VK_FORMAT_R8G8B8A8_SNORM);
  std::vector<SpecializationValue> specialization{specializationValue(shader::kCacaoSpecDownsampled, f.settings.downsample)};
  ResourceId constants = f.constants;
  ResourceId source = f.generateNormals ? f.frame.depth() : f.frame.worldNormals();
  std::string shader = f.generateNormals ? "cacao/prepare_normals" : "cacao/prepare_normals_from_input";
  glm::uvec2 size = f.sizes.ssao;
  auto& pipelines = f.pipelines();
  f.g().addPass(
      cacaoPrepareNormalsPassName(f.settings, f.generateNormals),
      [&](graph::PassBuilder& b) {
        b.read(constants, Access::UniformRead);
        b.read(source, Access::SampledRead);
        b.write(normals);
      },
      [&pipelines, shader, specialization, constants, source, normals, size](graph::PassContext& ctx) {
        dispatchCompute(ctx, pipelines.get(shader, specialization), {constants, source, normals}, nullptr, size.x, size.y);
      });
  return normals;
}

struct Prepared {
  ResourceId depths = graph::kNoResource, normals = graph::kNoResource;
};

// FFX_CACAO_GenerateQ0..Q2 and FFX_CACAO_GenerateQ3Base (adaptiveBase): RG8 per layer.
ResourceId addGenerate(CacaoFrame& f, const Prepared& in, const std::string& passName, bool adaptiveBase) {
  ResourceId ssao = f.layerImage(adaptiveBase ? "cacao_ssao_base" : "cacao_ssao", f.sizes.ssao, VK_FORMAT_R8G8_UNORM);
  int quality = cacaoShaderQuality(f.settings.quality);
  std::vector<SpecializationValue> specialization{specializationValue(shader::kCacaoSpecQuality, quality),
                                                  specializationValue(shader::kCacaoSpecAdaptiveBase, adaptiveBase),
                                                  specializationValue(shader::kCacaoSpecHalf, cacaoTwoLayers(f.settings.quality))};
  ResourceId constants = f.constants;
  glm::uvec3 grid{f.sizes.ssao, f.layers};
  auto& pipelines = f.pipelines();
  f.g().addPass(
      passName,
      [&](graph::PassBuilder& b) {
        b.read(constants, Access::UniformRead);
        b.read(in.depths, Access::SampledRead);
        b.read(in.normals, Access::SampledRead);
        b.write(ssao);
      },
      [&pipelines, specialization, constants, in, ssao, grid](graph::PassContext& ctx) {
        const auto& pipeline = pipelines.get("cacao/generate", specialization);
        dispatchCompute(ctx, pipeline, {constants, in.depths, in.normals, ssao}, nullptr, 0,
                        groupsFor(pipeline, grid.x, grid.y, grid.z));
      });
  return ssao;
}

// FFX_CACAO_GenerateImportanceMap, then PostprocessImportanceMapA and B (B sums into the load counter).
ResourceId addImportanceMap(CacaoFrame& f, ResourceId base) {
  glm::uvec2 size = f.sizes.importanceMap;
  auto image = [&](const char* name) { return f.g().createImage(name, {size.x, size.y, VK_FORMAT_R8_UNORM}); };
  ResourceId raw = image("cacao_importance_raw"), a = image("cacao_importance_a"), map = image("cacao_importance_map");
  ResourceId constants = f.constants, counter = f.loadCounter;
  auto& pipelines = f.pipelines();
  f.g().addPass(
      "cacao_generate_importance_map",
      [&](graph::PassBuilder& b) {
        b.read(constants, Access::UniformRead);
        b.read(base, Access::SampledRead);
        b.write(raw);
      },
      [&pipelines, constants, base, raw, size](graph::PassContext& ctx) {
        dispatchCompute(ctx, pipelines.get("cacao/generate_importance_map"), {constants, base, raw}, nullptr, size.x, size.y);
      });
  f.g().addPass(
      "cacao_postprocess_importance_map_a",
      [&](graph::PassBuilder& b) {
        b.read(constants, Access::UniformRead);
        b.read(raw, Access::SampledRead);
        b.write(a);
      },
      [&pipelines, constants, raw, a, size](graph::PassContext& ctx) {
        dispatchCompute(ctx, pipelines.get("cacao/postprocess_importance_map_a"), {constants, {raw, {}, true}, a}, nullptr,
                        size.x, size.y);
      });
  f.g().addPass(
      "cacao_postprocess_importance_map_b",
      [&](graph::PassBuilder& b) {
        b.read(constants, Access::UniformRead);
        b.read(a, Access::SampledRead);
        b.write(map);
        b.read(counter, Access::StorageRead);  // atomic adds: a read and a write
        b.write(counter, Access::StorageWrite);
      },
      [&pipelines, constants, a, map, counter, size](graph::PassContext& ctx) {
        dispatchCompute(ctx, pipelines.get("cacao/postprocess_importance_map_b"), {constants, {a, {}, true}, map, counter},
                        nullptr, size.x, size.y);
      });
  return map;
}

// FFX_CACAO_GenerateQ3: the base pass's result plus importance-driven extra taps; with --debug
// adaptive_taps the counting build, whose counters are read back into report.json.
ResourceId addGenerateAdaptive(CacaoFrame& f, const Prepared& in, ResourceId base, ResourceId importance) {
  ResourceId ssao = f.layerImage("cacao_ssao", f.sizes.ssao, VK_FORMAT_R8G8_UNORM);
  std::vector<SpecializationValue> specialization{specializationValue(shader::kCacaoSpecQuality, 3)};
  bool countTaps = f.frame.wantsDebugView("adaptive_taps");
  ResourceId taps = graph::kNoResource;
  if (countTaps) {
    taps = f.g().createBuffer("cacao_adaptive_taps", {kAdaptiveTapCounters * sizeof(uint32_t)});
    f.g().addPass(
        "adaptive_taps_clear", [&](graph::PassBuilder& b) { b.write(taps, Access::ClearWrite); },
        [taps](graph::PassContext& ctx) {
          vkCmdFillBuffer(ctx.cmd, ctx.buffer(taps).buffer, 0, kAdaptiveTapCounters * sizeof(uint32_t), 0);
        });
  }
  ResourceId constants = f.constants, counter = f.loadCounter;
  glm::uvec3 grid{f.sizes.ssao, f.layers};
  auto& pipelines = f.pipelines();
  f.g().addPass(
      "cacao_generate_q3",
      [&](graph::PassBuilder& b) {
        b.read(constants, Access::UniformRead);
        b.read(in.depths, Access::SampledRead);
        b.read(in.normals, Access::SampledRead);
        b.read(counter, Access::StorageRead);
        b.read(importance, Access::SampledRead);
        b.read(base, Access::SampledRead);
        b.write(ssao);
        if (countTaps) {
          b.read(taps, Access::StorageRead);
          b.write(taps, Access::StorageWrite);
        }
      },
      [&pipelines, specialization, constants, in, counter, importance, base, ssao, taps, countTaps, grid](graph::PassContext& ctx) {
        if (countTaps) {
          const auto& pipeline = pipelines.get("cacao/generate_adaptive_taps", specialization);
          dispatchCompute(ctx, pipeline, {constants, in.depths, in.normals, counter, {importance, {}, true}, base, ssao, taps},
                          nullptr, 0, groupsFor(pipeline, grid.x, grid.y, grid.z));
        } else {
          const auto& pipeline = pipelines.get("cacao/generate_adaptive", specialization);
          dispatchCompute(ctx, pipeline, {constants, in.depths, in.normals, counter, {importance, {}, true}, base, ssao},
                          nullptr, 0, groupsFor(pipeline, grid.x, grid.y, grid.z));
        }
      });
  if (countTaps) f.frame.debugView("adaptive_taps", taps);
  return ssao;
}

// FFX_CACAO_EdgeSensitiveBlurN: blur_pass_count 3x3 passes in one dispatch per tile.
ResourceId addEdgeSensitiveBlur(CacaoFrame& f, ResourceId ssao) {
  ResourceId blurred = f.layerImage("cacao_ssao_blurred", f.sizes.ssao, VK_FORMAT_R8G8_UNORM);
  int passes = f.settings.blurPassCount;
  bool smallLayer = int(std::min(f.sizes.ssao.x, f.sizes.ssao.y)) < shader::kCacaoMaxBlurPasses;  // the mirror's periodic form
  std::vector<SpecializationValue> specialization{specializationValue(shader::kCacaoSpecBlurPasses, passes),
                                                  specializationValue(shader::kCacaoSpecHalf, cacaoTwoLayers(f.settings.quality)),
                                                  specializationValue(shader::kCacaoSpecSmallLayer, smallLayer)};
  // Each workgroup writes its 64x48 tile less blur_pass_count pixels on each side.
  uint32_t tileW = uint32_t(shader::kCacaoBlurTileWidth) * shader::kCacaoBlurWorkgroup - 2 * uint32_t(passes);
  uint32_t tileH = uint32_t(shader::kCacaoBlurTileHeight) * shader::kCacaoBlurWorkgroup - 2 * uint32_t(passes);
  DispatchGroups groups{(f.sizes.ssao.x + tileW - 1) / tileW, (f.sizes.ssao.y + tileH - 1) / tileH, f.layers};
  ResourceId constants = f.constants;
  auto& pipelines = f.pipelines();
  f.g().addPass(
      "cacao_edge_sensitive_blur",
      [&](graph::PassBuilder& b) {
        b.read(constants, Access::UniformRead);
        b.read(ssao, Access::SampledRead);
        b.write(blurred);
      },
      [&pipelines, specialization, constants, ssao, blurred, groups](graph::PassContext& ctx) {
        dispatchCompute(ctx, pipelines.get("cacao/edge_sensitive_blur", specialization), {constants, ssao, blurred}, nullptr, 0,
                        groups);
      });
  return blurred;
}

int reinterleaveVariant(CacaoQuality q, bool downsample) {
  if (q == CacaoQuality::Lowest) return shader::kCacaoVariantHalf;
  if (q == CacaoQuality::Low) return shader::kCacaoVariantNonSmart;
  if (q == CacaoQuality::Medium) return downsample ? shader::kCacaoVariantNonSmart : shader::kCacaoVariantSmart;
  return shader::kCacaoVariantSmart;
}

// FFX_CACAO_Apply / NonSmartApply / NonSmartHalfApply (native) or FFX_CACAO_UpscaleBilateral5x5*
// (downsampled): the layers reinterleaved into the frame-sized R8 output.
ResourceId addReinterleave(CacaoFrame& f, ResourceId ssao, ResourceId depths) {
  glm::uvec2 size = f.sizes.inputOutput;
  ResourceId ao = f.g().createImage("cacao_ao", {size.x, size.y, VK_FORMAT_R8_UNORM});
  std::vector<SpecializationValue> specialization{
      specializationValue(shader::kCacaoSpecVariant, reinterleaveVariant(f.settings.quality, f.settings.downsample))};
  ResourceId constants = f.constants, depth = f.frame.depth();
  bool upscale = f.settings.downsample;
  auto& pipelines = f.pipelines();
  f.g().addPass(
      cacaoReinterleavePassName(f.settings),
      [&](graph::PassBuilder& b) {
        b.read(constants, Access::UniformRead);
        b.read(ssao, Access::SampledRead);
        if (upscale) {
          b.read(depth, Access::SampledRead);
          b.read(depths, Access::SampledRead, Subresources::mip(0));
        }
        b.write(ao);
      },
      [&pipelines, specialization, constants, ssao, depth, depths, ao, upscale, size](graph::PassContext& ctx) {
        if (upscale) {
          // Each thread writes 2x2 output pixels.
          dispatchCompute(ctx, pipelines.get("cacao/upscale_bilateral", specialization),
                          {constants, {ssao, {}, true}, ssao, depth, {depths, Subresources::mip(0)}, ao}, nullptr,
                          (size.x + 1) / 2, (size.y + 1) / 2);
        } else {
          dispatchCompute(ctx, pipelines.get("cacao/apply", specialization), {constants, {ssao, {}, true}, ao}, nullptr, size.x,
                          size.y);
        }
      });
  return ao;
}

// --debug views of the deinterleaved buffers: the layers of MIP 0 tiled 2x2 into one RGBA16F image.
void addTiledDebugView(CacaoFrame& f, const std::string& name, ResourceId layers, glm::uvec2 layerSize, int firstChannel) {
  if (!f.frame.wantsDebugView(name)) return;
  glm::uvec2 size = 2u * layerSize;
  ResourceId tiled = f.g().createImage("debug_" + name, {size.x, size.y, VK_FORMAT_R16G16B16A16_SFLOAT});
  int mask = cacaoTwoLayers(f.settings.quality) ? 0b1001 : 0b1111;
  std::vector<SpecializationValue> specialization{specializationValue(shader::kCacaoSpecLayerMask, mask),
                                                  specializationValue(shader::kCacaoSpecFirstChannel, firstChannel)};
  auto& pipelines = f.pipelines();
  f.g().addPass(
      "debug_" + name,
      [&](graph::PassBuilder& b) {
        b.read(layers, Access::SampledRead, Subresources::mip(0));
        b.write(tiled);
      },
      [&pipelines, specialization, layers, tiled, size](graph::PassContext& ctx) {
        dispatchCompute(ctx, pipelines.get("cacao/debug_tile_layers", specialization), {{layers, Subresources::mip(0)}, tiled},
                        nullptr, size.x, size.y);
      });
  f.frame.debugView(name, tiled);
}

}  // namespace

ResourceId addCacaoPasses(FrameBuilder& frame, const CacaoSettings& settings) {
  CacaoFrame f{frame, settings, cacaoBufferSizes(frame.size(), settings.downsample)};
  f.generateNormals = cacaoGeneratesNormals(settings, frame.capture());
  f.layers = cacaoTwoLayers(settings.quality) ? 2u : 4u;

  addClearLoadCounter(f);
  Prepared prepared{addPrepareDepths(f), addPrepareNormals(f)};
  ResourceId ssao;
  if (cacaoAdaptive(settings.quality)) {
    ResourceId base = addGenerate(f, prepared, "cacao_generate_q3_base", true);
    ResourceId importance = addImportanceMap(f, base);
    ssao = addGenerateAdaptive(f, prepared, base, importance);
    frame.debugView("importance_map", importance);
  } else {
    ssao = addGenerate(f, prepared, cacaoGeneratePassName(settings), false);
  }
  ResourceId blurred = settings.blurPassCount > 0 ? addEdgeSensitiveBlur(f, ssao) : ssao;
  ResourceId ao = addReinterleave(f, blurred, prepared.depths);

  addTiledDebugView(f, "deinterleaved_depth", prepared.depths, f.sizes.deinterleavedDepth, 0);
  addTiledDebugView(f, "deinterleaved_normals", prepared.normals, f.sizes.ssao, 0);
  addTiledDebugView(f, "edges", ssao, f.sizes.ssao, 1);
  addTiledDebugView(f, "ssao_raw", ssao, f.sizes.ssao, 0);
  frame.debugView("ao", ao);
  return ao;
}

}  // namespace aor
