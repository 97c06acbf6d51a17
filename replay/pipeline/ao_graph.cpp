#include "pipeline/ao_graph.h"

#include <string>
#include <utility>

namespace aor {

HistoryStates historyStatesAfter(const graph::RenderGraph& graph, const graph::CompiledGraph& compiled) {
  std::map<std::pair<std::string, bool>, graph::ImageState> next;  // (base, current next frame) -> state
  for (graph::ResourceId id = 0; id < graph.resources().size(); ++id) {
    const auto& decl = graph.resources()[id];
    if (decl.kind == graph::ResourceKind::History && compiled.resources[id].used)
      next[{decl.historyBase, !decl.historyCurrent}] = compiled.resources[id].finalState;
  }
  return [next = std::move(next)](const std::string& base, bool current) {
    auto it = next.find({base, current});
    return it == next.end() ? graph::ImageState{} : it->second;
  };
}

graph::RenderGraph buildHistoryPoisonGraph(const AoFrameInputs& in, const HistoryStates& historyStates, float value) {
  graph::RenderGraph g;
  auto history = g.createHistory(kAoHistory, {uint32_t(in.camera.width), uint32_t(in.camera.height), aoFormat(in.settings.bent != 0)},
                                 true, historyStates(kAoHistory, false), historyStates(kAoHistory, true));
  addFillPass(g, history.previous, value);
  return g;
}

AoFrameGraph buildAoFrameGraph(const AoFrameInputs& in, PassPipelines& pipelines, const HistoryStates& historyStates,
                               const AoFrameBuffers& buffers) {
  auto historyStateOf = [&](const char* base, bool current) {
    return historyStates ? historyStates(base, current) : graph::ImageState{};
  };
  AoFrameGraph frame;
  auto& g = frame.graph;
  const auto& cam = in.camera;
  const auto& settings = in.settings;
  uint32_t w = uint32_t(cam.width), h = uint32_t(cam.height);
  bool bent = settings.bent != 0;

  // The G-buffer is uploaded anew every frame, so its images are transients: once their last
  // reader has run, their memory can hold later images (aliasing).
  auto depth = g.createImage(kDepthImage, {w, h, VK_FORMAT_R32_SFLOAT});
  auto normals = in.hasNormals ? g.createImage(kNormalsImage, {w, h, VK_FORMAT_R16G16B16A16_SFLOAT}) : graph::kNoResource;
  addUploadPass(g, *buffers.depthUpload, depth, buffers.normalsUpload, normals);

  // With a temporal pass the linear distance is kept as history: the depth test of its second
  // rejection layer needs last frame's.
  graph::HistoryPair distanceHistory, aoHistory;
  graph::ResourceId distance;
  if (in.temporalWanted) {
    distanceHistory = g.createHistory(kDistanceHistory, {w, h, VK_FORMAT_R32_SFLOAT}, in.historyValid,
                                      historyStateOf(kDistanceHistory, false), historyStateOf(kDistanceHistory, true));
    distance = distanceHistory.current;
  } else {
    distance = g.createImage("view_distance", {w, h, VK_FORMAT_R32_SFLOAT});
  }
  addLinearizeDepthPass(g, pipelines, cam, depth, distance);

  auto reconstructed = addReconstructNormalsPass(g, pipelines, cam, distance);
  GtaoInputs gtaoInputs{distance, in.hasNormals ? normals : reconstructed, !in.hasNormals};
  auto noisy = addGtaoPass(g, pipelines, cam, settings, gtaoInputs);
  // The screen-space reference replaces GTAO (still declared, so the graph shows it culled) and is
  // never denoised.
  bool reference = settings.technique == AoTechnique::Reference;
  if (reference) {
    noisy = addGtaoReferencePass(g, pipelines, cam, settings, gtaoInputs);
    frame.notes["gtao"] = "technique=reference";
  }
  auto blurred = addSpatialPass(g, pipelines, cam, settings, noisy, distance);
  auto denoised = settings.spatial && !reference ? blurred : noisy;
  frame.finalAo = denoised;

  if (in.temporalWanted) {
    aoHistory = g.createHistory(kAoHistory, {w, h, aoFormat(bent)}, in.historyValid,
                                historyStateOf(kAoHistory, false), historyStateOf(kAoHistory, true));
    TemporalInputs t{denoised, distance, aoHistory.previous, distanceHistory.previous, aoHistory.current,
                     in.previousCamera};
    frame.finalAo = addTemporalPass(g, pipelines, cam, settings, t);
  } else {
    // Declared anyway so the compiled graph shows it culled, with the reason.
    auto filtered = g.createImage("ao_filtered", {w, h, aoFormat(bent)});
    TemporalInputs t{denoised, distance, graph::kNoResource, graph::kNoResource, filtered, in.previousCamera};
    addTemporalPass(g, pipelines, cam, settings, t);
    frame.notes["temporal"] = settings.temporal <= 0.0f ? "temporal=0" : "single-frame replay: no history";
    // Half-resolution AO still has to reach the frame's size; the temporal pass does it otherwise.
    if (settings.halfRes)
      frame.finalAo = addUpsamplePass(g, pipelines, cam, settings, denoised, distance,
                                      g.createImage("ao_upsampled", {w, h, aoFormat(bent)}));
  }
  if (!settings.spatial) frame.notes["spatial"] = frame.notes["spatial_columns"] = "spatial=0";
  if (in.hasNormals) frame.notes["reconstruct_normals"] = "the capture has normals";
  addReadbackPass(g, frame.finalAo, *buffers.readback);
  return frame;
}

}  // namespace aor
