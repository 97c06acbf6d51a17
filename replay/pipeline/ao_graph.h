#pragma once
// Assembles one frame's render graph from the capture's layout and the run's settings. Every pass
// of seed 000 is declared; what a run does not need (normal reconstruction when the capture has
// normals, spatial with spatial=0, temporal for single frames or temporal=0) is left unread and
// culled by compile(), which records why.
#include <map>
#include <string>

#include "graph/render_graph.h"
#include "passes/passes.h"
#include "pipeline/settings.h"

namespace aor {

class GraphResources;

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

// `resources` supplies the states of persistent images; null when only inspecting the graph.
AoFrameGraph buildAoFrameGraph(const AoFrameInputs& inputs, PassPipelines& pipelines, const GraphResources* resources,
                               const AoFrameBuffers& buffers);

}  // namespace aor
