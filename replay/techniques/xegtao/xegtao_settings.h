#pragma once
// XeGTAO (seed 002): a run's settings as XeGTAO.h's GTAOSettings holds them, and its main pass
// (the other passes are the shared horizon blocks, shared_passes/horizon_blocks.h).
#include "shared_passes/horizon_blocks.h"
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

  // What the shared blocks read.
  shared_passes::HorizonBlockSettings blocks() const {
    return {radius, radiusMultiplier, falloffRange, finalValuePower, sampleDistributionPower, thinOccluderCompensation,
            depthMipSamplingOffset, denoisePasses, depth32, bent};
  }
};

XeGtaoSettings xegtaoSettings(const Settings& settings);

// Pass 2, between the shared depth chain and denoiser: the working term and edges.
using XeGtaoWorking = shared_passes::HorizonWorking;
XeGtaoWorking addXeGtaoMainPass(FrameBuilder& frame, const XeGtaoSettings& settings, graph::ResourceId depthMips);

}  // namespace aor
