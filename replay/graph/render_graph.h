#pragma once
// Frame graph in the Frostbite/Filament shape: passes declare the images and buffers they read and
// write in a setup step; compile() culls passes whose outputs nothing consumes, computes lifetimes,
// assigns transients to shared memory slots (aliasing) and derives every barrier and layout
// transition from the declared accesses, per mip level and array layer. Nothing here touches a
// GPU, so the graph is unit-tested without one; its runtime (replay/runtime/: executor.h,
// physical_resources.h, pass_context.h) records a compiled graph into a command buffer.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <vulkan/vulkan_core.h>

namespace aor {
struct GpuImage;
struct GpuBuffer;
}  // namespace aor

namespace aor::graph {

using ResourceId = uint32_t;
inline constexpr ResourceId kNoResource = ~0u;

struct ImageDesc {
  uint32_t width = 0;
  uint32_t height = 0;
  VkFormat format = VK_FORMAT_UNDEFINED;
  uint32_t mipLevels = 1;    // level m is max(1, width >> m) x max(1, height >> m)
  uint32_t arrayLayers = 1;
};
struct BufferDesc {
  uint64_t bytes = 0;
};
uint32_t bytesPerPixel(VkFormat format);  // formats the passes use; 0 for unknown
uint64_t imageBytes(const ImageDesc& desc);  // every mip level of every layer

enum class ResourceKind : uint8_t {
  Transient,  // lives within one execution; may share memory with others whose lifetimes do not overlap
  Imported,   // owned outside the graph (uploaded inputs, read-back targets); never aliased
  History,    // one half of a history pair: persists across frames, never aliased
};
enum class ResourceType : uint8_t { Image, Buffer };

// ClearWrite is vkCmdClearColorImage or vkCmdFillBuffer: a transfer write in the CLEAR stage.
// StorageRead/StorageWrite are storage images or storage buffers, by the resource's type;
// UniformRead and IndirectRead are for buffers only, SampledRead for images only.
// AccelerationStructureRead is a shader's ray queries against the acceleration structure a buffer
// holds (GpuBuffer::accelerationStructure), which the dispatch binds as one.
enum class Access : uint8_t {
  SampledRead, StorageRead, StorageWrite, TransferRead, TransferWrite, ClearWrite, UniformRead, IndirectRead,
  AccelerationStructureRead
};

// Synchronisation state of an image subresource or a buffer: what last touched it and, for
// images, in which layout it was left (buffers stay UNDEFINED).
struct ResourceState {
  VkPipelineStageFlags2 stage = VK_PIPELINE_STAGE_2_NONE;
  VkAccessFlags2 access = VK_ACCESS_2_NONE;
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
};
// Stage, access mask and layout that one declared access needs (of an image; buffers ignore the
// layout); writes() tells hazards apart.
ResourceState requiredState(Access access);
bool isWrite(Access access);

// A range of mip levels and array layers; the defaults mean the whole image. kAll counts are
// "to the last level (layer)"; resolve() turns them into numbers for an image.
struct Subresources {
  static constexpr uint32_t kAll = ~0u;
  uint32_t baseMip = 0, mipCount = kAll;
  uint32_t baseLayer = 0, layerCount = kAll;
  static Subresources mip(uint32_t level) { return {level, 1, 0, kAll}; }
  static Subresources layer(uint32_t index) { return {0, kAll, index, 1}; }
  Subresources resolve(const ImageDesc& desc) const;
  bool operator==(const Subresources&) const = default;
};

struct PassContext;  // defined by the runtime: command buffer and physical resources

class PassBuilder {
 public:
  void read(ResourceId id, Access access = Access::SampledRead, Subresources range = {});
  void write(ResourceId id, Access access = Access::StorageWrite, Subresources range = {});
  // A write that is dropped (and its resource left unallocated) when no live pass reads it: a pass
  // that fills several inputs at once (the upload of every capture input) writes only those read.
  // The pass's execute callback checks PassContext::has() before touching it.
  void writeIfRead(ResourceId id, Access access = Access::StorageWrite, Subresources range = {});
  // A pass with side effects (e.g. read-back to the host) is a root: never culled.
  void sideEffect();

 private:
  friend class RenderGraph;
  PassBuilder(class RenderGraph& graph, uint32_t pass) : graph_(graph), pass_(pass) {}
  void declare(ResourceId id, Access access, Subresources range, bool asWrite, bool ifRead);
  class RenderGraph& graph_;
  uint32_t pass_;
};

struct ResourceDecl {
  std::string name;
  ImageDesc desc;           // images
  BufferDesc buffer;        // buffers
  ResourceType type = ResourceType::Image;
  ResourceKind kind = ResourceKind::Transient;
  ResourceState initialState;  // Imported/History: state left by earlier work (every subresource); Transient: UNDEFINED
  std::vector<ResourceState> initialStates;  // when not empty: per subresource (layer * mips + mip), overriding initialState
  // Imported only: the runtime object behind it, owned by whoever imported it (a technique's BVH,
  // a staging buffer). Null: the runtime keeps a persistent one by name.
  const GpuImage* externalImage = nullptr;
  const GpuBuffer* externalBuffer = nullptr;
  std::string historyBase;  // History: the pair's name ("ao_history"; `name` adds .previous/.current)
  bool historyCurrent = false;  // History: the image this frame writes
  bool isBuffer() const { return type == ResourceType::Buffer; }
  uint32_t subresourceCount() const { return isBuffer() ? 1 : desc.mipLevels * desc.arrayLayers; }
  uint64_t bytes() const { return isBuffer() ? buffer.bytes : imageBytes(desc); }
  const ResourceState& initialStateOf(uint32_t subresource) const {
    return initialStates.empty() ? initialState : initialStates.at(subresource);
  }
};

struct AccessDecl {
  ResourceId resource = kNoResource;
  Access access = Access::SampledRead;
  Subresources range;   // resolved against the image (whole buffer for buffers)
  bool ifRead = false;  // declared with writeIfRead
};

struct PassDecl {
  std::string name;
  std::vector<AccessDecl> accesses;  // in declaration order
  bool sideEffect = false;
  std::function<void(PassContext&)> execute;
};

struct HistoryPair {
  ResourceId previous = kNoResource;  // last frame's output; kNoResource when history is invalid
  ResourceId current = kNoResource;   // written this frame, becomes `previous` next frame
};

struct Barrier {
  ResourceId resource = kNoResource;
  ResourceState before;    // src stage/access and old layout (UNDEFINED when contents are discarded)
  ResourceState after;     // dst stage/access and new layout
  Subresources range;   // the mips and layers it covers (resolved; whole buffer for buffers)
};

struct CompiledPass {
  uint32_t pass = 0;                    // index into RenderGraph::passes()
  std::vector<Barrier> barriersBefore;  // recorded just before the pass
  std::vector<bool> accessLive;         // per PassDecl::accesses entry: false for a dropped writeIfRead
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
  VkImageUsageFlags usage = 0;   // images: union over the live accesses
  VkBufferUsageFlags bufferUsage = 0;  // buffers: likewise
  ResourceState finalState;     // state after the last live access (executors carry it to the next frame)
  std::vector<ResourceState> finalStates;  // per subresource (mip-major within each layer: layer * mips + mip)
};

struct MemorySlot {
  uint64_t bytes = 0;                  // largest member, by ResourceDecl::bytes()
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
  ResourceId importImage(std::string name, ImageDesc desc, ResourceState initialState = {});
  ResourceId createBuffer(std::string name, BufferDesc desc);
  ResourceId importBuffer(std::string name, BufferDesc desc, ResourceState initialState = {});
  // Imports whose runtime object the caller owns (see ResourceDecl::externalImage/externalBuffer).
  ResourceId importExternalImage(std::string name, ImageDesc desc, const GpuImage& image, ResourceState initialState = {});
  ResourceId importExternalBuffer(std::string name, BufferDesc desc, const GpuBuffer& buffer, ResourceState initialState = {});
  // History images are explicit: `current` always exists; `previous` only when previousValid.
  HistoryPair createHistory(std::string name, ImageDesc desc, bool previousValid,
                            ResourceState previousState = {}, ResourceState currentState = {});
  // Per-subresource states left by earlier work, for an imported or history image whose mips or
  // layers were left differently (layer * mips + mip).
  void setInitialStates(ResourceId id, std::vector<ResourceState> states);
  uint32_t addPass(std::string name, const std::function<void(PassBuilder&)>& setup,
                   std::function<void(PassContext&)> execute = {});

  CompiledGraph compile() const;
  // The declarations alone: no pass's recording function, no imported resource's runtime object
  // (what a report may keep after the frame's resources are gone).
  RenderGraph withoutRuntime() const;

  const std::vector<ResourceDecl>& resources() const { return resources_; }
  const std::vector<PassDecl>& passes() const { return passes_; }

 private:
  friend class PassBuilder;
  ResourceId add(ResourceDecl decl);
  std::vector<ResourceDecl> resources_;
  std::vector<PassDecl> passes_;
};

// A frame's graph kept as data after it ran: its declarations and what compile() made of them.
// Reports describe it (describe, toDot, graphResourcesJson).
struct GraphSnapshot {
  RenderGraph declared;
  CompiledGraph compiled;
};
GraphSnapshot snapshotOf(const RenderGraph& graph, const CompiledGraph& compiled);

// Human-readable explanation (passes run and culled with reasons, resources with lifetimes,
// sizes, formats and aliasing, barriers) and Graphviz DOT of a compiled graph.
std::string describe(const RenderGraph& graph, const CompiledGraph& compiled);
std::string toDot(const RenderGraph& graph, const CompiledGraph& compiled);
const char* formatName(VkFormat format);

// --- Helpers for the runtime and for reports ---
// State a pass needs for the subresources `range` of `id`: the union of requiredState() over the
// pass's live accesses that overlap it. Where those accesses need different layouts (e.g. sampled
// read + storage write of one image) the layout is GENERAL. This is the layout the runtime must
// put in that pass's descriptors, and the `after` state of any barrier the graph emits for it.
// {NONE, NONE, UNDEFINED} if untouched. The range defaults to the whole resource.
ResourceState requiredState(const PassDecl& pass, ResourceId id, Subresources range = {});
// Whether two resolved ranges share a subresource.
bool overlaps(const Subresources& a, const Subresources& b);
const char* accessName(Access access);             // "sampled read", "storage write", ...
const char* kindName(ResourceKind kind);           // "transient", "imported", "history"
const char* layoutName(VkImageLayout layout);      // "SHADER_READ_ONLY_OPTIMAL", ...
std::string stageNames(VkPipelineStageFlags2 stages);  // "COMPUTE_SHADER|COPY", "NONE"
std::string accessNames(VkAccessFlags2 access);        // "SHADER_SAMPLED_READ", "NONE"
std::string rangeText(const ResourceDecl& decl, const Subresources& range);  // "" for a whole single-level image
// Name of the compiled pass at `index` (into CompiledGraph::passes), "-" when out of range.
std::string passName(const RenderGraph& graph, const CompiledGraph& compiled, int index);
// The other resources sharing `id`'s memory slot (none when it has no slot).
std::vector<ResourceId> aliasesOf(const CompiledGraph& compiled, ResourceId id);

}  // namespace aor::graph
