// Linear view distance from depth, and normals reconstructed from it when a capture has none.
#include "linearize_depth.h"
#include "passes/passes.h"
#include "pipeline/pass_context.h"
#include "reconstruct_normals.h"

namespace aor {

graph::ResourceId addLinearizeDepthPass(graph::RenderGraph& graph, PassPipelines& pipelines, const FrameCamera& camera,
                                        graph::ResourceId depth, graph::ResourceId distanceTarget) {
  auto params = projectionParams(camera.projection, camera.width, camera.height);
  shader::LinearizeConstants constants{};
  constants.size = {camera.width, camera.height};
  constants.projection22 = params.projection22;
  constants.projection32 = params.projection32;
  constants.reversedDepth = params.reversedDepth ? 1u : 0u;
  graph.addPass(
      "linearize_depth",
      [&](graph::PassBuilder& b) {
        b.read(depth, graph::Access::StorageRead);
        b.write(distanceTarget);
      },
      [&pipelines, constants, depth, distanceTarget](graph::PassContext& ctx) {
        dispatchCompute(ctx, pipelines.linearizeDepth(), {depth, distanceTarget}, &constants,
                        uint32_t(constants.size.x), uint32_t(constants.size.y));
      });
  return distanceTarget;
}

graph::ResourceId addReconstructNormalsPass(graph::RenderGraph& graph, PassPipelines& pipelines,
                                            const FrameCamera& camera, graph::ResourceId distance) {
  auto params = projectionParams(camera.projection, camera.width, camera.height);
  shader::ReconstructNormalsConstants constants{};
  constants.ndcToViewMul = params.ndcToViewMul;
  constants.ndcToViewAdd = params.ndcToViewAdd;
  constants.invSize = {1.0f / float(camera.width), 1.0f / float(camera.height)};
  constants.size = {camera.width, camera.height};
  auto normals = graph.createImage("normals_reconstructed",
                                   {uint32_t(camera.width), uint32_t(camera.height), VK_FORMAT_R16G16B16A16_SFLOAT});
  graph.addPass(
      "reconstruct_normals",
      [&](graph::PassBuilder& b) {
        b.read(distance);
        b.write(normals);
      },
      [&pipelines, constants, distance, normals](graph::PassContext& ctx) {
        dispatchCompute(ctx, pipelines.reconstructNormals(), {distance, normals}, &constants,
                        uint32_t(constants.size.x), uint32_t(constants.size.y));
      });
  return normals;
}

}  // namespace aor
