#pragma once
// Physical images and buffers behind a compiled render graph. Transients are bound into shared
// memory slots as compile() assigned them (aliasing); imported and history resources own their
// memory (or are the caller's, for external imports), keep their contents and synchronisation
// state across frames, and history pairs swap roles each frame.
#include <map>
#include <string>
#include <vector>

#include "runtime/pass_context.h"
#include "graph/render_graph.h"
#include "vk/resources.h"

namespace aor {

struct VulkanContext;

class PhysicalResources {
 public:
  explicit PhysicalResources(VulkanContext& vk) : vk_(vk) {}
  ~PhysicalResources();
  PhysicalResources(const PhysicalResources&) = delete;
  PhysicalResources& operator=(const PhysicalResources&) = delete;

  // State the history pair `base`'s previous or current image was left in, for createHistory.
  graph::ResourceState historyState(const std::string& base, bool current) const;
  // State an imported resource (external or not) was left in by the last execution that used it;
  // none (UNDEFINED) before that. What the next frame's import must declare.
  graph::ResourceState importedState(const std::string& name) const;
  // Physical image or buffer of every used resource, indexed by ResourceId (null where unused).
  std::vector<graph::PhysicalResource> prepare(const graph::RenderGraph& graph, const graph::CompiledGraph& compiled);
  // Carries final states of imported and history resources over to the next execution.
  void keepFinalStates(const graph::RenderGraph& graph, const graph::CompiledGraph& compiled);
  // Makes this frame's history current next frame's previous.
  void swapHistory();
  // Frees all history images (reset on a size change: they are re-created at the new size).
  void dropHistory();

 private:
  struct Persistent {
    GpuImage image;
    GpuBuffer buffer;
    std::vector<graph::ResourceState> states;  // per subresource
  };
  std::string historyKey(const std::string& base, bool current) const;  // "<base>#0|1"
  std::string physicalKey(const graph::ResourceDecl& decl) const;
  Persistent& persistent(const graph::ResourceDecl& decl);
  void prepareTransients(const graph::RenderGraph& graph, const graph::CompiledGraph& compiled);
  void releaseTransients();
  void destroy(Persistent& p);

  VulkanContext& vk_;
  std::map<std::string, Persistent> persistent_;  // imported by name; history by "<base>#0|1"
  std::map<std::string, int> historyParity_;      // history base name -> physical index of "current"
  std::map<std::string, std::vector<graph::ResourceState>> externalStates_;  // external imports by name (they own nothing here)
  std::string transientSignature_;
  std::map<std::string, GpuImage> transientImages_;
  std::map<std::string, GpuBuffer> transientBuffers_;
  std::vector<GpuMemory> slots_;
};

}  // namespace aor
