#pragma once
// Building blocks every technique can add to its frame: the shared front (capture inputs, linear
// distance, view-space normals), seed 000's spatial and temporal denoisers with their keys, and the
// host's copies (upload, read-back, debug read-backs). Technique modules call these; the host
// declares the front and the read-backs around a technique's own passes (techniques/built_frame.cpp).
#include <optional>
#include <vector>

#include "graph/render_graph.h"
#include "technique_api/frame_builder.h"
#include "vk/resources.h"

namespace aor::shared_passes {

// Host staging buffers of one frame in flight (null where the capture lacks the input).
struct FrontBuffers {
  const GpuBuffer* depth = nullptr;    // R32F, row 0 at the top
  const GpuBuffer* normals = nullptr;  // RGBA16F world normals
  const GpuBuffer* depth2 = nullptr;   // R32F second layer
};

// Declares the front into `frame`: `depth`, `normals`, `depth2` images filled by one `upload` pass
// (each copy made only when something reads it), `linearize_depth` (into the distance history's
// current image when `keepDistance`), `reconstruct_normals` and `view_normals`. Whatever no live pass
// reads is culled.
void declareFront(FrameBuilder& frame, const FrontBuffers& buffers, bool keepDistance);

// --- Seed 000's denoisers, as blocks with their own keys ---
Parameter spatialParameter();                       // `spatial` 0/1, default 1
Parameter temporalParameter(double defaultWeight);  // `temporal` history weight 0..0.98, 0 = no temporal pass
inline constexpr const char* kSpatialKey = "spatial";
inline constexpr const char* kTemporalKey = "temporal";
// The temporal block keeps history (AO and linear distance) when temporal > 0.
HistoryNeeds temporalDenoiseHistory(const Settings& settings);
// The same settings with the temporal block off (temporal = 0): the replay the ghosting metrics
// compare against on captures without references (Technique::withoutHistory).
std::optional<Settings> withoutTemporalDenoise(const Settings& settings);

// AO images the denoisers read and write: RGBA16F (bent.xyz, visibility) or R16F (visibility).
VkFormat aoImageFormat(bool bent);
struct DenoiseInput {
  graph::ResourceId ao;  // aoImageFormat(bent), the frame's size divided by `divisor` (rounded up)
  bool bent = false;
  int divisor = 1;       // 2: half resolution; the temporal block (or `upsample`) brings it to full size
};
// `spatial_columns` + `spatial` (the 5x5 path-weighted bilateral), declared always; returns the
// blurred image with spatial=1, else `in.ao` (and the passes are culled, with the reason).
graph::ResourceId addSpatialDenoise(FrameBuilder& frame, const DenoiseInput& in);
// `temporal` (reprojection, 3-layer rejection, EMA with history) at the frame's size, declared
// always; with temporal=0 or a single frame it is culled, and a half-resolution input is brought to
// full size by `upsample` instead. Returns the frame's final AO.
graph::ResourceId addTemporalDenoise(FrameBuilder& frame, const DenoiseInput& in);

// --- Copies of the host ---
// Copies `image` into a host-visible buffer; a root of the graph.
void addReadbackPass(graph::RenderGraph& graph, graph::ResourceId image, const GpuBuffer& target);
// Copies a debug view's level (or buffer) into its host buffer, as `debug:NAME`; a root.
void addDebugReadbackPass(graph::RenderGraph& graph, const DebugReadback& readback);
// Fills every channel of `image` with `value` (a side effect: never culled). Test-only fault
// injection (ReplayOptions::testPoisonHistoryAt).
void addFillPass(graph::RenderGraph& graph, graph::ResourceId image, float value);

}  // namespace aor::shared_passes
