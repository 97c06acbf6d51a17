#pragma once
// Frame graph in the Frostbite/Filament shape: passes declare the images they read and write in a
// setup step; compile() culls passes whose outputs nothing consumes, computes lifetimes, assigns
// transients to shared memory slots (aliasing) and derives every barrier and layout transition from
// the declared accesses. Nothing here touches a GPU, so the graph is unit-tested without one;
// graph/executor (in aor_gpu) records a compiled graph into a command buffer.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <vulkan/vulkan_core.h>

namespace aor::graph {

using ResourceId = uint32_t;
inline constexpr ResourceId kNoResource = ~0u;

struct ImageDesc {
  uint32_t width = 0;
  uint32_t height = 0;
  VkFormat format = VK_FORMAT_UNDEFINED;
};
uint32_t bytesPerPixel(VkFormat format);  // formats the passes use; 0 for unknown
uint64_t imageBytes(const ImageDesc& desc);

enum class ResourceKind : uint8_t {
  Transient,  // lives within one execution; may share memory with others whose lifetimes do not overlap
  Imported,   // owned outside the graph (uploaded inputs, read-back targets); never aliased
  History,    // one half of a history pair: persists across frames, never aliased
};

// ClearWrite is vkCmdClearColorImage: a transfer write in its own pipeline stage (CLEAR, not COPY).
enum class Access : uint8_t { SampledRead, StorageRead, StorageWrite, TransferRead, TransferWrite, ClearWrite };

// Synchronisation state of an image: what last touched it and in which layout it was left.
struct ImageState {
  VkPipelineStageFlags2 stage = VK_PIPELINE_STAGE_2_NONE;
  VkAccessFlags2 access = VK_ACCESS_2_NONE;
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
};
// Stage, access mask and layout that one declared access needs; writes() tells hazards apart.
ImageState requiredState(Access access);
bool isWrite(Access access);

struct PassContext;  // defined by the executor: command buffer and physical images

class PassBuilder {
 public:
  void read(ResourceId id, Access access = Access::SampledRead);
  void write(ResourceId id, Access access = Access::StorageWrite);
  // A pass with side effects (e.g. read-back to the host) is a root: never culled.
  void sideEffect();

 private:
  friend class RenderGraph;
  PassBuilder(class RenderGraph& graph, uint32_t pass) : graph_(graph), pass_(pass) {}
  void declare(ResourceId id, Access access, bool asWrite);  // read() and write(), checked alike
  class RenderGraph& graph_;
  uint32_t pass_;
};

struct ResourceDecl {
  std::string name;
  ImageDesc desc;
  ResourceKind kind = ResourceKind::Transient;
  ImageState initialState;  // Imported/History: state left by earlier work; Transient: UNDEFINED
  std::string historyBase;  // History: the pair's name ("ao_history"; `name` adds .previous/.current)
  bool historyCurrent = false;  // History: the image this frame writes
};

struct PassDecl {
  std::string name;
  std::vector<std::pair<ResourceId, Access>> accesses;  // in declaration order
  bool sideEffect = false;
  std::function<void(PassContext&)> execute;
};

struct HistoryPair {
  ResourceId previous = kNoResource;  // last frame's output; kNoResource when history is invalid
  ResourceId current = kNoResource;   // written this frame, becomes `previous` next frame
};

struct Barrier {
  ResourceId resource = kNoResource;
  ImageState before;  // src stage/access and old layout (UNDEFINED when contents are discarded)
  ImageState after;   // dst stage/access and new layout
};

struct CompiledPass {
  uint32_t pass = 0;                    // index into RenderGraph::passes()
  std::vector<Barrier> barriersBefore;  // recorded just before the pass
};

struct CulledPass {
  uint32_t pass = 0;
  std::string reason;  // e.g. "writes ao_blurred, which no live pass reads"
};

struct CompiledResource {
  bool used = false;         // touched by a live pass; unused resources get no memory at all
  int firstPass = -1;        // index into CompiledGraph::passes
  int lastPass = -1;
  int memorySlot = -1;       // Transient only: resources with the same slot share memory
  VkImageUsageFlags usage = 0;  // union over the live accesses
  ImageState finalState;     // state after the last live access (executors carry it to the next frame)
};

struct MemorySlot {
  uint64_t bytes = 0;                  // largest member, by imageBytes()
  std::vector<ResourceId> resources;   // members in order of first use; lifetimes never overlap
};

struct CompiledGraph {
  std::vector<CompiledPass> passes;         // live passes in execution order
  std::vector<CulledPass> culled;
  std::vector<CompiledResource> resources;  // indexed by ResourceId
  std::vector<MemorySlot> slots;
  uint64_t transientBytes = 0;              // sum of slot sizes
  uint64_t persistentBytes = 0;             // used Imported + History resources
  uint64_t peakBytes() const { return transientBytes + persistentBytes; }
  // Transient bytes without aliasing (every used transient on its own), for reports.
  uint64_t unaliasedTransientBytes = 0;
};

class RenderGraph {
 public:
  ResourceId createImage(std::string name, ImageDesc desc);
  ResourceId importImage(std::string name, ImageDesc desc, ImageState initialState = {});
  // History images are explicit: `current` always exists; `previous` only when previousValid.
  HistoryPair createHistory(std::string name, ImageDesc desc, bool previousValid,
                            ImageState previousState = {}, ImageState currentState = {});
  uint32_t addPass(std::string name, const std::function<void(PassBuilder&)>& setup,
                   std::function<void(PassContext&)> execute = {});

  CompiledGraph compile() const;

  const std::vector<ResourceDecl>& resources() const { return resources_; }
  const std::vector<PassDecl>& passes() const { return passes_; }

 private:
  friend class PassBuilder;
  std::vector<ResourceDecl> resources_;
  std::vector<PassDecl> passes_;
};

// Human-readable explanation (passes run and culled with reasons, resources with lifetimes,
// sizes, formats and aliasing, barriers) and Graphviz DOT of a compiled graph.
std::string describe(const RenderGraph& graph, const CompiledGraph& compiled);
std::string toDot(const RenderGraph& graph, const CompiledGraph& compiled);
const char* formatName(VkFormat format);

// --- Additions beyond the original contract (helpers for the executor and for reports) ---
// State a pass needs for one resource: the union of requiredState() over the pass's accesses to
// it. Where those accesses need different layouts (e.g. sampled read + storage write of one image)
// the layout is GENERAL. This is the layout the executor must put in that pass's descriptors, and
// the `after` state of any barrier the graph emits for it. {NONE, NONE, UNDEFINED} if untouched.
ImageState requiredState(const PassDecl& pass, ResourceId id);
const char* accessName(Access access);             // "sampled read", "storage write", ...
const char* kindName(ResourceKind kind);           // "transient", "imported", "history"
const char* layoutName(VkImageLayout layout);      // "SHADER_READ_ONLY_OPTIMAL", ...
std::string stageNames(VkPipelineStageFlags2 stages);  // "COMPUTE_SHADER|COPY", "NONE"
std::string accessNames(VkAccessFlags2 access);        // "SHADER_SAMPLED_READ", "NONE"
// Name of the compiled pass at `index` (into CompiledGraph::passes), "-" when out of range.
std::string passName(const RenderGraph& graph, const CompiledGraph& compiled, int index);
// The other resources sharing `id`'s memory slot (none when it has no slot).
std::vector<ResourceId> aliasesOf(const CompiledGraph& compiled, ResourceId id);

}  // namespace aor::graph
