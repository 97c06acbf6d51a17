// The screen-space reference (`--technique reference`, shaders/reference/gtao_reference.comp): the
// GTAO integral of seed 000 over kReferenceSlices noise-free slices and every pixel out to the
// radius, never denoised. Its error against the ray-traced reference is the screen-space
// assumption's alone; GTAO's error against it is sampling's and denoising's. `sweep` uses it as the
// reference of captures without a ray-traced one.
#include <fmt/format.h>

#include "shared_passes/shared_passes.h"
#include "runtime/pass_context.h"
#include "techniques/gtao/gtao_pass.h"
#include "techniques/registry.h"

namespace aor {
namespace {

constexpr int kReferenceSlices = 32;

void addReferencePass(FrameBuilder& frame, const Settings& settings) {
  GtaoSettings g = gtaoSettings(settings);  // radius, falloff, power, thin and bent: the same meaning as gtao's
  GtaoInputs inputs = gtaoInputs(frame);
  auto constants = gtaoConstants(frame.camera(), g);
  auto ao = frame.graph().createImage("ao_reference", {frame.size().x, frame.size().y, shared_passes::aoImageFormat(g.bent)});
  std::vector<SpecializationValue> specialization{specializationValue(shader::kGtaoSpecSlices, kReferenceSlices),
                                                  specializationValue(shader::kGtaoSpecBent, g.bent),
                                                  specializationValue(shader::kGtaoSpecViewNormals, inputs.viewSpaceNormals),
                                                  specializationValue(shader::kGtaoSpecThin, g.thin > 0.0f)};
  auto& pipelines = frame.pipelines();
  frame.graph().addPass(
      "gtao_reference",
      [&](graph::PassBuilder& b) {
        b.read(inputs.distance);
        b.read(inputs.normals);
        b.write(ao);
      },
      [&pipelines, specialization, constants, inputs, ao](graph::PassContext& ctx) {
        dispatchCompute(ctx, pipelines.get("reference/gtao_reference", specialization), {inputs.distance, inputs.normals, ao},
                        &constants, uint32_t(constants.size.x), uint32_t(constants.size.y));
      });
  frame.setOutput(ao, g.bent ? OutputLayout::bentThenVisibility() : OutputLayout::visibilityOnly());
}

Technique makeReference() {
  const Technique& gtao = gtaoTechnique();
  Technique t;
  t.name = "reference";
  t.seed = "";
  t.summary = fmt::format("the GTAO integral evaluated exhaustively on the depth buffer ({} noise-free slices, every "
                          "pixel out to the radius), never denoised: slow, the screen-space yardstick", kReferenceSlices);
  // The keys of gtao's integral, with gtao's defaults and ranges.
  for (const char* key : {kRadiusKey, "falloff", "power", "thin", "bent"}) t.parameters.push_back(*gtao.parameter(key));
  t.addPasses = addReferencePass;
  return t;
}

}  // namespace

const Technique& referenceTechnique() {
  static const Technique t = makeReference();
  return t;
}

}  // namespace aor
