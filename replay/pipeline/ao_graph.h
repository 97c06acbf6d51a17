#pragma once
// Assembles one frame's render graph from the capture's layout and the run's settings. Every pass
// of seed 000 is declared; what a run does not need (normal reconstruction when the capture has
// normals, spatial with spatial=0, temporal for single frames or temporal=0) is left unread and
// culled by compile(), which records why.
#include <functional>
#include <map>
#include <string>

#include "graph/render_graph.h"
#include "passes/passes.h"
#include "pipeline/settings.h"

namespace aor {

struct AoFrameInputs {
  FrameCamera camera;
  FrameCamera previousCamera;  // meaningful only with historyValid
  bool hasNormals = true;      // the capture carries world-space normals
  bool temporalWanted = false; // multi-frame replay with temporal > 0: history images exist
  bool historyValid = false;   // previous frame's history may be read
  AoSettings settings;
};

struct AoFrameBuffers {
  const GpuBuffer* depthUpload = nullptr;    // R32F depth, row 0 at the top
  const GpuBuffer* normalsUpload = nullptr;  // RGBA16F world normals (null without normals)
  const GpuBuffer* readback = nullptr;       // receives the final AO image
};

struct AoFrameGraph {
  graph::RenderGraph graph;
  graph::ResourceId finalAo = graph::kNoResource;
  std::map<std::string, std::string> notes;  // pass name -> the setting or input that made it unneeded
};

inline constexpr const char* kDepthImage = "depth";
inline constexpr const char* kNormalsImage = "normals";
inline constexpr const char* kAoHistory = "ao_history";
inline constexpr const char* kDistanceHistory = "distance_history";

// The state earlier frames left a history image in (`base` as kAoHistory; `current`: the image this
// frame writes). In a replay, GraphResources tracks it; empty means nothing ran before (UNDEFINED).
using HistoryStates = std::function<graph::ImageState(const std::string& base, bool current)>;

AoFrameGraph buildAoFrameGraph(const AoFrameInputs& inputs, PassPipelines& pipelines, const HistoryStates& historyStates,
                               const AoFrameBuffers& buffers);

// The history states the frame after `graph` starts from, for tools that compile frames without
// running them (`aoreplay graph`): its `current` images become `previous`, and it writes into the
// images that were `previous` (UNDEFINED where there was none, as after a replay's first frame).
// The same bookkeeping as GraphResources::keepFinalStates and swapHistory.
HistoryStates historyStatesAfter(const graph::RenderGraph& graph, const graph::CompiledGraph& compiled);

// Test-only fault injection (ReplayOptions::testPoisonHistoryAt): one pass that fills the AO
// history's `previous` image with `value`, so a test can show on a real device what the temporal
// pass makes of history no correct frame can leave (NaN, Inf). Never part of a normal replay.
graph::RenderGraph buildHistoryPoisonGraph(const AoFrameInputs& inputs, const HistoryStates& historyStates, float value);

}  // namespace aor
