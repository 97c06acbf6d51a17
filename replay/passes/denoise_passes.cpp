// Passes 2 and 3 of seed 000: spatial bilateral blur and temporal reprojection with history.
#include "passes/passes.h"
#include "pipeline/pass_context.h"
#include "spatial_denoise.h"
#include "temporal_denoise.h"

namespace aor {

graph::ResourceId addSpatialPass(graph::RenderGraph& graph, PassPipelines& pipelines, const FrameCamera& camera,
                                 const AoSettings& settings, graph::ResourceId ao, graph::ResourceId distance) {
  bool bent = settings.bent != 0;
  bool halfResolution = settings.halfRes != 0;
  shader::SpatialConstants constants{};
  constants.size = aoWorkingSize(camera, settings);
  uint32_t w = uint32_t(constants.size.x), h = uint32_t(constants.size.y);
  auto columnSum = graph.createImage("ao_column_sum", {w, h, aoFormat(bent)});
  auto columnWeightAndEdge = graph.createImage("ao_column_weight_edge", {w, h, VK_FORMAT_R16G16_SFLOAT});
  auto blurred = graph.createImage("ao_blurred", {w, h, aoFormat(bent)});
  // The 5x5 blur in two dispatches, vertical legs then rows (why: shaders/spatial_denoise.h).
  graph.addPass(
      "spatial_columns",
      [&](graph::PassBuilder& b) {
        b.read(ao, graph::Access::StorageRead);
        b.read(distance, graph::Access::StorageRead);
        b.write(columnSum);
        b.write(columnWeightAndEdge);
      },
      [&pipelines, bent, halfResolution, constants, ao, distance, columnSum, columnWeightAndEdge](graph::PassContext& ctx) {
        dispatchCompute(ctx, pipelines.spatialColumns(bent, halfResolution),
                        {ao, distance, columnSum, columnWeightAndEdge}, &constants,
                        uint32_t(constants.size.x), uint32_t(constants.size.y));
      });
  graph.addPass(
      "spatial",
      [&](graph::PassBuilder& b) {
        b.read(ao, graph::Access::StorageRead);
        b.read(columnSum, graph::Access::StorageRead);
        b.read(columnWeightAndEdge, graph::Access::StorageRead);
        b.write(blurred);
      },
      [&pipelines, bent, constants, ao, columnSum, columnWeightAndEdge, blurred](graph::PassContext& ctx) {
        dispatchCompute(ctx, pipelines.spatial(bent),
                        {ao, columnSum, columnWeightAndEdge, blurred},
                        &constants, uint32_t(constants.size.x), uint32_t(constants.size.y));
      });
  return blurred;
}

namespace {

// The temporal shader as `temporal` (blending history when there is some) or as `upsample`.
graph::ResourceId addTemporalShaderPass(const char* name, graph::RenderGraph& graph, PassPipelines& pipelines,
                                        const FrameCamera& camera, const AoSettings& settings, const TemporalInputs& in) {
  bool bent = settings.bent != 0;
  bool halfResolution = settings.halfRes != 0;
  bool hasHistory = in.historyAo != graph::kNoResource && in.historyDistance != graph::kNoResource;
  auto constants = shader::temporalReprojection(camera.view, camera.projection, in.previousCamera.view,
                                                in.previousCamera.projection, camera.width, camera.height);
  constants.blend = settings.temporal;
  // Without history the shader variant never reads bindings 2-3; the current AO and distance (of
  // the formats those bindings declare) stand in so every binding is valid and no pass declares a
  // read of a history image that does not exist.
  graph::ResourceId historyAo = hasHistory ? in.historyAo : in.current;
  graph::ResourceId historyDistance = hasHistory ? in.historyDistance : in.distance;
  graph.addPass(
      name,
      [&](graph::PassBuilder& b) {
        b.read(in.current, graph::Access::StorageRead);
        b.read(in.distance, graph::Access::StorageRead);
        if (hasHistory) {
          b.read(in.historyAo, graph::Access::StorageRead);
          b.read(in.historyDistance, graph::Access::StorageRead);
        }
        b.write(in.target);
      },
      [&pipelines, bent, hasHistory, halfResolution, constants, in, historyAo, historyDistance](graph::PassContext& ctx) {
        dispatchCompute(ctx, pipelines.temporal(bent, hasHistory, halfResolution),
                        {in.current, in.distance, historyAo, historyDistance, in.target},
                        &constants, uint32_t(constants.size.x), uint32_t(constants.size.y));
      });
  return in.target;
}

}  // namespace

graph::ResourceId addTemporalPass(graph::RenderGraph& graph, PassPipelines& pipelines, const FrameCamera& camera,
                                  const AoSettings& settings, const TemporalInputs& inputs) {
  return addTemporalShaderPass("temporal", graph, pipelines, camera, settings, inputs);
}

graph::ResourceId addUpsamplePass(graph::RenderGraph& graph, PassPipelines& pipelines, const FrameCamera& camera,
                                  const AoSettings& settings, graph::ResourceId current, graph::ResourceId distance,
                                  graph::ResourceId target) {
  TemporalInputs inputs{current, distance, graph::kNoResource, graph::kNoResource, target, camera};
  return addTemporalShaderPass("upsample", graph, pipelines, camera, settings, inputs);
}

}  // namespace aor
