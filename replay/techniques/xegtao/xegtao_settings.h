#pragma once
// XeGTAO (seed 002): a run's settings as XeGTAO.h's GTAOSettings holds them, and the per-frame
// constants of its three passes (XeGTAO.h GTAOUpdateConstants, from this tool's camera).
#include "technique_api/frame_builder.h"
#include "technique_api/settings.h"
#include "xegtao/xegtao.h"

namespace aor {

struct XeGtaoSettings {
  float radius = 0.5f;
  int slices = 3, steps = 3;  // XeGTAO's High
  float radiusMultiplier = shader::kXeGtaoDefaultRadiusMultiplier;
  float falloffRange = shader::kXeGtaoDefaultFalloffRange;
  float sampleDistributionPower = shader::kXeGtaoDefaultSampleDistributionPower;
  float thinOccluderCompensation = shader::kXeGtaoDefaultThinOccluderCompensation;
  float finalValuePower = shader::kXeGtaoDefaultFinalValuePower;
  float depthMipSamplingOffset = shader::kXeGtaoDefaultDepthMipSamplingOffset;
  int denoisePasses = 1;
  bool depth32 = false;
  bool bent = false;
  float temporal = 0.0f;
};

XeGtaoSettings xegtaoSettings(const Settings& settings);

// GTAOUpdateConstants for this frame: XeGTAO's view space (x right, y up, z forward) is this
// tool's with z flipped and x, y flipped where the capture's projection points them the other way.
shader::XeGtaoConstants xegtaoConstants(const FrameCamera& camera, const XeGtaoSettings& settings);

// The three passes; each returns what it writes.
struct XeGtaoWorking {
  graph::ResourceId aoTerm = graph::kNoResource;  // R8_UINT (R32_UINT with bent normals)
  graph::ResourceId edges = graph::kNoResource;   // R8_UNORM
};
// The 5-level view-z chain (R16F, R32F with depth32).
graph::ResourceId addXeGtaoPrefilter(FrameBuilder& frame, const XeGtaoSettings& settings);
XeGtaoWorking addXeGtaoMainPass(FrameBuilder& frame, const XeGtaoSettings& settings, graph::ResourceId depthMips);
// denoise_passes dispatches; the last writes R16F visibility (RGBA16F bent.xyz + visibility).
graph::ResourceId addXeGtaoDenoise(FrameBuilder& frame, const XeGtaoSettings& settings, const XeGtaoWorking& working);
// Not XeGTAO's: the shared front's sky rule applied to the denoised output in place (sky.comp).
void addXeGtaoSky(FrameBuilder& frame, const XeGtaoSettings& settings, graph::ResourceId denoised);
// --debug screen_radius: the main pass's screen-space radius per pixel (R32F).
graph::ResourceId addXeGtaoScreenRadius(FrameBuilder& frame, const XeGtaoSettings& settings, graph::ResourceId depthMips);

}  // namespace aor
