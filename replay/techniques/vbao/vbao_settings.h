#pragma once
// vbao: a run's settings, and its main pass (the depth chain, denoiser and sky pass are the shared
// horizon blocks, shared_passes/horizon_blocks.h).
#include "shared_passes/horizon_blocks.h"
#include "technique_api/frame_builder.h"
#include "technique_api/settings.h"
#include "vbao/vbao.h"

namespace aor {

enum class VbaoWeighting { Uniform, Cosine };

struct VbaoSettings {
  float radius = 0.5f;
  int slices = 3, steps = 3;  // Bevy's High
  float thickness = shader::kVbaoDefaultThickness;
  int sectors = int(shader::kVbaoMaxSectors);
  VbaoWeighting weighting = VbaoWeighting::Cosine;
  float radiusMultiplier = shader::kVbaoDefaultRadiusMultiplier;
  float falloffRange = shader::kVbaoDefaultFalloffRange;
  float sampleDistributionPower = shader::kVbaoDefaultSampleDistributionPower;
  float finalValuePower = shader::kVbaoDefaultFinalValuePower;
  float depthMipSamplingOffset = shader::kVbaoDefaultDepthMipSamplingOffset;
  int denoisePasses = 1;
  bool depth32 = false;
  float temporal = 0.0f;

  // What the shared blocks read (no bent normals, no thin-occluder falloff: the slab is that).
  shared_passes::HorizonBlockSettings blocks() const {
    return {radius, radiusMultiplier, falloffRange, finalValuePower, sampleDistributionPower, 0.0f,
            depthMipSamplingOffset, denoisePasses, depth32, false};
  }
};

VbaoSettings vbaoSettings(const Settings& settings);

// The bitmask pass, between the shared depth chain and denoiser: the working term and edges.
shared_passes::HorizonWorking addVbaoMainPass(FrameBuilder& frame, const VbaoSettings& settings, graph::ResourceId depthMips);

}  // namespace aor
