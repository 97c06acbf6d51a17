#pragma once
// Physical images behind a compiled render graph. Transients are bound into shared memory slots
// as compile() assigned them (aliasing); imported and history images own their memory, keep their
// contents and synchronisation state across frames, and history pairs swap roles each frame.
#include <map>
#include <string>
#include <vector>

#include "graph/render_graph.h"
#include "vk/resources.h"

namespace aor {

struct VulkanContext;

class GraphResources {
 public:
  explicit GraphResources(VulkanContext& vk) : vk_(vk) {}
  ~GraphResources();
  GraphResources(const GraphResources&) = delete;
  GraphResources& operator=(const GraphResources&) = delete;

  // State the history pair `base`'s previous or current image was left in, for createHistory.
  graph::ImageState historyState(const std::string& base, bool current) const;
  // Physical image of every used resource, indexed by ResourceId (null where unused).
  std::vector<const GpuImage*> prepare(const graph::RenderGraph& graph, const graph::CompiledGraph& compiled);
  // Carries final states of imported and history images over to the next execution.
  void keepFinalStates(const graph::RenderGraph& graph, const graph::CompiledGraph& compiled);
  // Makes this frame's history current next frame's previous.
  void swapHistory();
  // Frees all history images (reset on a size change: they are re-created at the new size).
  void dropHistory();

 private:
  struct Persistent {
    GpuImage image;
    graph::ImageState state;
  };
  std::string historyKey(const std::string& base, bool current) const;  // "<base>#0|1"
  std::string physicalKey(const graph::ResourceDecl& decl) const;
  Persistent& persistent(const graph::ResourceDecl& decl);
  void prepareTransients(const graph::RenderGraph& graph, const graph::CompiledGraph& compiled);
  void releaseTransients();

  VulkanContext& vk_;
  std::map<std::string, Persistent> persistent_;  // imported by name; history by "<base>#0|1"
  std::map<std::string, int> historyParity_;      // history base name -> physical index of "current"
  std::string transientSignature_;
  std::map<std::string, GpuImage> transients_;
  std::vector<GpuMemory> slots_;
};

}  // namespace aor
