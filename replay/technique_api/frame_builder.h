#pragma once
// What a technique's addPasses() gets for one frame: the frame's render graph with the shared front
// already declared (capture inputs, linear distance, view-space normals; whatever nothing reads is
// culled), the camera, history, the pipelines, and where to put its output. The host
// (built_frame.cpp) adds the read-back of the output and of any debug views afterwards.
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "graph/render_graph.h"
#include "technique_api/frame_camera.h"
#include "technique_api/settings.h"
#include "vk/pipeline_cache.h"

namespace aor {

// Where the final visibility (and bent normals) sit in the output image, whatever its format.
struct OutputLayout {
  int visibilityChannel = 0;
  int bentChannel = -1;  // first of three (x, y, z), or -1 without bent normals
  static OutputLayout visibilityOnly() { return {0, -1}; }
  static OutputLayout bentThenVisibility() { return {3, 0}; }  // RGBA: bent.xyz, visibility
};

// The state earlier frames left a history image in (`base` as "ao_history"; `current`: the image
// this frame writes). In a replay the graph's runtime tracks it; empty means nothing ran before.
using HistoryStates = std::function<graph::ResourceState(const std::string& base, bool current)>;

// One debug view or counter the run asked for, read back after the frame.
struct DebugReadback {
  std::string name;
  graph::ResourceId resource = graph::kNoResource;
  graph::Subresources range;  // images: one level of one layer
  VkFormat format = VK_FORMAT_UNDEFINED;  // images; UNDEFINED for a buffer (read as uint32 counters)
  uint32_t width = 0, height = 0;         // of the level read back
  const GpuBuffer* target = nullptr;
};

class FrameBuilder {
 public:
  struct Setup {
    const Settings* settings = nullptr;
    FrameCamera camera, previousCamera;  // previousCamera: meaningful only with historyValid
    CaptureLayout capture;
    bool historyWanted = false;  // multi-frame replay and the technique keeps history under these settings
    bool historyValid = false;   // last frame's history may be read
    HistoryStates historyStates;
    std::set<std::string> debugViews;  // --debug names asked for
    // Host buffers for debug read-backs, by view name and size (null: debug views are declared
    // into the graph but read back nowhere, as for `aoreplay graph`).
    std::function<const GpuBuffer*(const std::string& name, uint64_t bytes)> debugTarget;
    TechniqueState* state = nullptr;
  };
  FrameBuilder(graph::RenderGraph& graph, PipelineCache& pipelines, Setup setup);

  graph::RenderGraph& graph() { return graph_; }
  PipelineCache& pipelines() { return pipelines_; }
  const Settings& settings() const { return *setup_.settings; }
  const FrameCamera& camera() const { return setup_.camera; }
  const FrameCamera& previousCamera() const { return setup_.previousCamera; }
  const CaptureLayout& capture() const { return setup_.capture; }
  bool historyWanted() const { return setup_.historyWanted; }
  bool historyValid() const { return setup_.historyValid; }
  glm::uvec2 size() const { return {uint32_t(setup_.camera.width), uint32_t(setup_.camera.height)}; }

  // The shared front. Every one exists (or is kNoResource where the capture lacks the input);
  // what no live pass reads is culled and never allocated.
  graph::ResourceId depth() const { return front_.depth; }                 // R32F as captured
  graph::ResourceId worldNormals() const { return front_.worldNormals; }   // RGBA16F world space, or kNoResource
  graph::ResourceId depth2() const { return front_.depth2; }               // R32F second layer, or kNoResource
  graph::ResourceId linearDistance() const { return front_.distance; }     // R32F view distance along -Z, sky -1
  graph::ResourceId reconstructedNormals() const { return front_.reconstructedNormals; }  // RGBA16F view space, from depth
  graph::ResourceId viewNormals() const { return front_.viewNormals; }     // RGBA16F view space: rotated, else reconstructed
  // Last frame's linear distance: kNoResource unless history is valid and the technique's
  // HistoryNeeds asked for it.
  graph::ResourceId previousDistance() const { return front_.previousDistance; }

  // A history image pair of the technique's own; `previous` is kNoResource when history is invalid.
  graph::HistoryPair history(const std::string& name, graph::ImageDesc desc);

  // The frame's result: `image` at the frame's size, read back and written as the `visibility`
  // channel (and bent.X/Y/Z) whatever its format.
  void setOutput(graph::ResourceId image, OutputLayout layout);
  graph::ResourceId output() const { return output_; }
  const OutputLayout& outputLayout() const { return outputLayout_; }

  // Why a pass that compile() culls is not needed (the setting or input behind it).
  void explain(const std::string& pass, const std::string& why) { notes_[pass] = why; }
  const std::map<std::string, std::string>& notes() const { return notes_; }

  // A debug view the technique declared: read back when the run asked for it. Images: one level of
  // one layer; buffers: the whole buffer, read as 32-bit unsigned counters into report.json.
  bool wantsDebugView(const std::string& name) const { return setup_.debugViews.count(name) > 0; }
  void debugView(const std::string& name, graph::ResourceId resource, graph::Subresources range = {0, 1, 0, 1});
  const std::vector<DebugReadback>& debugReadbacks() const { return debug_; }

  // A number of this frame's that report.json records as `frames[i].technique.KEY` (an
  // accumulation's sample count).
  void reportValue(const std::string& key, double value) { values_[key] = value; }
  const std::map<std::string, double>& reportValues() const { return values_; }

  template <typename T>
  T& state() {
    auto* s = dynamic_cast<T*>(setup_.state);
    if (!s) throw std::logic_error("technique state missing or of another type");
    return *s;
  }

  struct Front {
    graph::ResourceId depth = graph::kNoResource, worldNormals = graph::kNoResource, depth2 = graph::kNoResource,
                      distance = graph::kNoResource, reconstructedNormals = graph::kNoResource,
                      viewNormals = graph::kNoResource, previousDistance = graph::kNoResource;
  };
  // The host declares the front before the technique runs (shared_passes/front.cpp).
  void setFront(const Front& front) { front_ = front; }
  graph::ResourceState historyState(const std::string& base, bool current) const;

 private:
  graph::RenderGraph& graph_;
  PipelineCache& pipelines_;
  Setup setup_;
  Front front_;
  graph::ResourceId output_ = graph::kNoResource;
  OutputLayout outputLayout_;
  std::map<std::string, std::string> notes_;
  std::vector<DebugReadback> debug_;
  std::map<std::string, double> values_;
};

}  // namespace aor
