// Pass 1 of seed 000: GTAO horizon search (shaders/gtao.comp, math in shaders/gtao.h).
#include "gtao.h"
#include "passes/passes.h"
#include "pipeline/pass_context.h"

namespace aor {

shader::GtaoConstants gtaoConstants(const FrameCamera& camera, const AoSettings& settings) {
  auto params = projectionParams(camera.projection, camera.width, camera.height);
  shader::GtaoConstants c{};
  c.worldToView0 = glm::vec4(camera.view[0][0], camera.view[0][1], camera.view[0][2], 0.0f);
  c.worldToView1 = glm::vec4(camera.view[1][0], camera.view[1][1], camera.view[1][2], 0.0f);
  c.worldToView2 = glm::vec4(camera.view[2][0], camera.view[2][1], camera.view[2][2], 0.0f);
  c.ndcToViewMul = params.ndcToViewMul;
  c.ndcToViewAdd = params.ndcToViewAdd;
  c.invSize = {1.0f / float(camera.width), 1.0f / float(camera.height)};
  c.size = {camera.width, camera.height};
  c.radius = settings.radius;
  c.pixelsPerUnit = params.pixelsPerUnit;
  c.falloffRange = settings.falloff;
  c.thin = settings.thin;
  c.power = settings.power;
  c.frameIndex = camera.frameIndex;
  c.viewPerPixel = params.viewPerPixel;
  return c;
}

int aoResolutionDivisor(const AoSettings& settings) { return settings.halfRes ? 2 : 1; }

glm::ivec2 aoWorkingSize(const FrameCamera& camera, const AoSettings& settings) {
  return shader::reducedSize(glm::ivec2(camera.width, camera.height), aoResolutionDivisor(settings));
}

graph::ResourceId addGtaoPass(graph::RenderGraph& graph, PassPipelines& pipelines, const FrameCamera& camera,
                              const AoSettings& settings, const GtaoInputs& inputs) {
  bool bent = settings.bent != 0;
  auto constants = gtaoConstants(camera, settings);
  glm::uvec2 size(aoWorkingSize(camera, settings));
  auto ao = graph.createImage("ao_noisy", {size.x, size.y, aoFormat(bent)});
  graph.addPass(
      "gtao",
      [&](graph::PassBuilder& b) {
        b.read(inputs.distance, graph::Access::StorageRead);
        b.read(inputs.normals, graph::Access::StorageRead);
        b.write(ao);
      },
      [&pipelines, slices = settings.slices, steps = settings.steps, bent, thin = settings.thin > 0.0f,
       halfResolution = settings.halfRes != 0, constants, inputs, ao, size](graph::PassContext& ctx) {
        dispatchCompute(ctx, pipelines.gtao(slices, steps, bent, inputs.viewSpaceNormals, thin, halfResolution),
                        {inputs.distance, inputs.normals, ao}, &constants, size.x, size.y);
      });
  return ao;
}

}  // namespace aor
