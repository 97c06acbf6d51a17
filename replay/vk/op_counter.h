#pragma once
// Counts what the passes of a replay execute, per dispatch: the texture and image accesses its
// shader really made (the counting build of each shader, shaders/counting/count_ops.glsl, adds one
// to a counter per access) and the bytes of the images and buffers it binds, read and written.
// While a VulkanContext has an OpCounter, pipelines are built from the counting build and every
// dispatch gets its own zeroed slot of one host-visible buffer. A bench's floor per pass comes from
// these counts (bench/floor.h); they do not depend on the device.
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "vk/dispatch.h"
#include "vk/resources.h"

namespace aor {

struct VulkanContext;

// The name suffix of a shader's counting build in the embedded index ("gtao/gtao@count").
inline constexpr std::string_view kCountingBuildSuffix = "@count";

// The counters of count_ops.glsl, in its order.
enum class OpKind : uint32_t { Fetch, Sample, Gather, ImageLoad, ImageStore };
inline constexpr size_t kOpKinds = 5;
const char* opKindName(OpKind kind);  // "texel_fetch", "texture_lod", "gather", "image_load", "image_store"

struct DispatchCounts {
  std::string pass;
  std::array<uint64_t, kOpKinds> ops{};
  uint64_t bytesRead = 0;     // of the bound subresources a live access reads (each once)
  uint64_t bytesWritten = 0;  // of those a live access writes
  uint64_t invocations = 0;   // workgroups x workgroup size
  uint64_t dispatches = 1;    // summed per pass by lastFramePerPass
  uint64_t op(OpKind kind) const { return ops[size_t(kind)]; }
  // Accesses through the texture path: fetches, filtered samples, gathers and image loads.
  uint64_t textureReads() const;
};

class OpCounter {
 public:
  explicit OpCounter(VulkanContext& vk, uint32_t maxDispatches = 4096);
  ~OpCounter();
  OpCounter(const OpCounter&) = delete;
  OpCounter& operator=(const OpCounter&) = delete;

  // A zeroed slot for one dispatch of `pass`, what the counting pipeline's AoOpCounts binding receives.
  BoundResource slot(const std::string& pass, uint64_t bytesRead, uint64_t bytesWritten, uint64_t invocations);
  // Every dispatch since construction, in recording order, with its counters as the GPU left them:
  // call it once the work has completed.
  std::vector<DispatchCounts> dispatches() const;

 private:
  VulkanContext& vk_;
  GpuBuffer buffer_;
  uint32_t maxDispatches_;
  std::vector<DispatchCounts> recorded_;
};

// Per pass, the counts of the last run of its dispatches in `dispatches` (the last frame's, when a
// replay ran several), for the passes in `passes`, in that order; a pass without dispatches is left out.
std::vector<DispatchCounts> lastFramePerPass(const std::vector<DispatchCounts>& dispatches,
                                             const std::vector<std::string>& passes);

}  // namespace aor
