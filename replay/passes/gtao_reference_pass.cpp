// Screen-space reference technique (`technique=reference`): shaders/gtao_reference.comp.
#include "passes/passes.h"
#include "pipeline/pass_context.h"

namespace aor {

graph::ResourceId addGtaoReferencePass(graph::RenderGraph& graph, PassPipelines& pipelines, const FrameCamera& camera,
                                       const AoSettings& settings, const GtaoInputs& inputs) {
  bool bent = settings.bent != 0;
  auto constants = gtaoConstants(camera, settings);
  auto ao = graph.createImage("ao_reference", {uint32_t(camera.width), uint32_t(camera.height), aoFormat(bent)});
  graph.addPass(
      "gtao_reference",
      [&](graph::PassBuilder& b) {
        b.read(inputs.distance);
        b.read(inputs.normals);
        b.write(ao);
      },
      [&pipelines, bent, thin = settings.thin > 0.0f, constants, inputs, ao](graph::PassContext& ctx) {
        dispatchCompute(ctx, pipelines.gtaoReference(kReferenceSlices, bent, inputs.viewSpaceNormals, thin),
                        {inputs.distance, inputs.normals, ao}, &constants,
                        uint32_t(constants.size.x), uint32_t(constants.size.y));
      });
  return ao;
}

}  // namespace aor
