// vbao's main pass: xegtao's samples, each a slab marking sectors of its slice (shaders/vbao/).
#include <algorithm>
#include <bit>

#include "runtime/pass_context.h"
#include "techniques/vbao/vbao_settings.h"

namespace aor {
namespace {

// sectors=0 ties them to the samples of a slice, as Bevy does.
int sectorCount(const VbaoSettings& s) { return s.sectors > 0 ? s.sectors : std::min(2 * s.steps, int(shader::kVbaoMaxSectors)); }

std::vector<SpecializationValue> mainPassSpecialization(const VbaoSettings& s) {
  return {specializationValue(shader::kVbaoSpecSlices, s.slices), specializationValue(shader::kVbaoSpecSteps, s.steps),
          specializationValue(shader::kVbaoSpecSectors, sectorCount(s)),
          specializationValue(shader::kVbaoSpecCosine, s.weighting == VbaoWeighting::Cosine),
          specializationValue(shader::kHorizonSpecDepth32, s.depth32),
          {uint32_t(shader::kVbaoSpecSampleDistributionPower), std::bit_cast<uint32_t>(s.sampleDistributionPower)}};
}

}  // namespace

shared_passes::HorizonWorking addVbaoMainPass(FrameBuilder& frame, const VbaoSettings& settings, graph::ResourceId depthMips) {
  glm::uvec2 size = frame.size();
  auto& g = frame.graph();
  shared_passes::HorizonWorking out;
  out.aoTerm = g.createImage("ao_term", {size.x, size.y, shared_passes::horizonTermFormat(false)});
  out.edges = g.createImage("edges", {size.x, size.y, VK_FORMAT_R8_UNORM});
  const bool sectorsView = frame.wantsDebugView("sectors");
  graph::ResourceId sectors = sectorsView ? g.createImage("sectors", {size.x, size.y, VK_FORMAT_R32_SFLOAT}) : graph::kNoResource;
  shader::VbaoConstants push{shared_passes::horizonConstants(frame.camera(), settings.blocks()), settings.thickness};
  auto specialization = mainPassSpecialization(settings);
  auto normals = frame.viewNormals();
  auto& pipelines = frame.pipelines();
  g.addPass(
      "vbao_main",
      [&](graph::PassBuilder& b) {
        b.read(depthMips, graph::Access::SampledRead);
        b.read(normals, graph::Access::StorageRead);
        b.write(out.aoTerm);
        b.write(out.edges);
        if (sectorsView) b.write(sectors);
      },
      [&pipelines, specialization, push, depthMips, normals, out, sectors, sectorsView, size](graph::PassContext& ctx) {
        if (sectorsView)
          dispatchCompute(ctx, pipelines.get("vbao/main_pass_sectors", specialization),
                          {depthMips, normals, out.aoTerm, out.edges, sectors}, &push, size.x, size.y);
        else
          dispatchCompute(ctx, pipelines.get("vbao/main_pass", specialization), {depthMips, normals, out.aoTerm, out.edges},
                          &push, size.x, size.y);
      });
  if (sectorsView) frame.debugView("sectors", sectors);
  return out;
}

}  // namespace aor
