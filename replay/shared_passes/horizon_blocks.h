#pragma once
// Blocks of the horizon-search techniques (xegtao, vbao), ported from XeGTAO (seed 002): the depth
// MIP chain (its prefilter pass), the edge-aware denoiser, the sky pass and the screen-radius debug
// pass, with the per-frame constants they read (shaders/horizon/horizon.h). A technique adds its
// own main pass between the chain and the denoiser: it writes the working term and edges.
#include <string>

#include "technique_api/frame_builder.h"
#include "horizon/horizon.h"

namespace aor::shared_passes {

// What the blocks read of a technique's settings, under XeGTAO's names.
struct HorizonBlockSettings {
  float radius = 0.5f;
  float radiusMultiplier = 1.0f;
  float falloffRange = 0.0f;  // the depth chain's filter falls off over this fraction of 0.75 x the radius
  float finalValuePower = 1.0f;
  float sampleDistributionPower = 1.0f;
  float thinOccluderCompensation = 0.0f;
  float depthMipSamplingOffset = 0.0f;
  int denoisePasses = 1;
  bool depth32 = false;  // R32F chain instead of R16F
  bool bent = false;     // bent normals in the working term and output
};

// GTAOUpdateConstants for this frame: XeGTAO's view space (x right, y up, z forward) is this
// tool's with z flipped and x, y flipped where the capture's projection points them the other way.
shader::HorizonConstants horizonConstants(const FrameCamera& camera, const HorizonBlockSettings& settings);

// The working term a main pass writes: R8_UINT visibility / 1.5 (R32_UINT RGBA8 with bent normals),
// and the packed edges (R8_UNORM).
VkFormat horizonTermFormat(bool bent);
struct HorizonWorking {
  graph::ResourceId aoTerm = graph::kNoResource;
  graph::ResourceId edges = graph::kNoResource;
};

// `passName`: the pass's name in the technique's graph (a technique keeps its own names).
// The 5-level view-z chain `depth_mips` (R16F, R32F with depth32; fewer levels for tiny frames).
graph::ResourceId addHorizonDepthMips(FrameBuilder& frame, const HorizonBlockSettings& settings, const std::string& passName);
// denoisePasses dispatches (the earlier ones named passName_N); the last writes `ao_denoised`,
// R16F visibility (RGBA16F bent.xyz + visibility).
graph::ResourceId addHorizonDenoise(FrameBuilder& frame, const HorizonBlockSettings& settings, const HorizonWorking& working,
                                    const std::string& passName);
// The shared front's sky rule applied to the denoised output in place (shaders/horizon/sky.comp).
void addHorizonSky(FrameBuilder& frame, const HorizonBlockSettings& settings, graph::ResourceId denoised,
                   const std::string& passName);
// --debug screen_radius: the main pass's screen-space radius per pixel (R32F).
graph::ResourceId addHorizonScreenRadius(FrameBuilder& frame, const HorizonBlockSettings& settings, graph::ResourceId depthMips,
                                         const std::string& passName);
// The chain's levels as debug views: `linear_depth` (MIP 0) and depth_mipK.
void addHorizonDepthViews(FrameBuilder& frame, graph::ResourceId depthMips);
// The declarations of the views the blocks provide (linear_depth, depth_mip1..4, view_normals,
// screen_radius, edges), for a technique's list before its own.
std::vector<DebugView> horizonDebugViews();

}  // namespace aor::shared_passes
