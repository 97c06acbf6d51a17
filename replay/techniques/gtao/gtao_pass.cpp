// Pass 1 of seed 000: GTAO horizon search (shaders/gtao/gtao.comp, math in shaders/gtao/gtao.h).
#include "shared_passes/shared_passes.h"
#include "shared_passes/camera.h"
#include "runtime/pass_context.h"
#include "techniques/gtao/gtao_pass.h"

namespace aor {
namespace {
}  // namespace

shader::GtaoConstants gtaoConstants(const FrameCamera& camera, const GtaoSettings& settings) {
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

glm::ivec2 aoWorkingSize(const FrameCamera& camera, const GtaoSettings& settings) {
  return shader::reducedSize(glm::ivec2(camera.width, camera.height), aoResolutionDivisor(settings));
}

GtaoInputs gtaoInputs(const FrameBuilder& frame) {
  bool captured = frame.worldNormals() != graph::kNoResource;
  return {frame.linearDistance(), captured ? frame.worldNormals() : frame.reconstructedNormals(), !captured};
}

graph::ResourceId addGtaoPass(FrameBuilder& frame, const GtaoSettings& settings, const GtaoInputs& inputs) {
  auto constants = gtaoConstants(frame.camera(), settings);
  glm::uvec2 size(aoWorkingSize(frame.camera(), settings));
  auto ao = frame.graph().createImage("ao_noisy", {size.x, size.y, shared_passes::aoImageFormat(settings.bent)});
  std::vector<SpecializationValue> specialization{
      specializationValue(shader::kGtaoSpecSlices, settings.slices), specializationValue(shader::kGtaoSpecSteps, settings.steps),
      specializationValue(shader::kGtaoSpecBent, settings.bent),     specializationValue(shader::kGtaoSpecViewNormals, inputs.viewSpaceNormals),
      specializationValue(shader::kGtaoSpecThin, settings.thin > 0.0f), specializationValue(shader::kGtaoSpecHalfResolution, settings.halfRes)};
  auto& pipelines = frame.pipelines();
  frame.graph().addPass(
      "gtao",
      [&](graph::PassBuilder& b) {
        b.read(inputs.distance, graph::Access::StorageRead);
        b.read(inputs.normals, graph::Access::StorageRead);
        b.write(ao);
      },
      [&pipelines, specialization, constants, inputs, ao, size](graph::PassContext& ctx) {
        dispatchCompute(ctx, pipelines.get("gtao/gtao", specialization), {inputs.distance, inputs.normals, ao}, &constants,
                        size.x, size.y);
      });
  return ao;
}

}  // namespace aor
