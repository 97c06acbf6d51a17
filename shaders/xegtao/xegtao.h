#ifndef AOR_XEGTAO_H
#define AOR_XEGTAO_H
// XeGTAO (seed 002) as a port: its main pass's specialisation ids and XeGTAO.h's defaults, shared
// by the shaders and C++; the constants struct, shared constants and noise are the horizon
// blocks' (horizon/horizon.h). Where each value comes from: replay/techniques/xegtao/README.md.
#include "../horizon/horizon.h"
#include "../common/shared_begin.h"

// Specialisation constant ids of the main pass (2, 4 and 6 are the shared blocks').
AOR_CONST int kXeGtaoSpecSlices = 0;
AOR_CONST int kXeGtaoSpecSteps = 1;
AOR_CONST int kXeGtaoSpecThin = 3;        // the thin-occluder falloff (thin_occluder_compensation > 0)
// sample_distribution_power as a compile-time value (its float bits): pow(s, 2) then compiles to
// s * s, as XeGTAO gets with XE_GTAO_USE_DEFAULT_CONSTANTS; a power per sample is most of the main
// pass's arithmetic on a CPU device.
AOR_CONST int kXeGtaoSpecSampleDistributionPower = 5;

// XeGTAO.h's defaults (XE_GTAO_DEFAULT_*).
AOR_CONST float kXeGtaoDefaultRadiusMultiplier = 1.457f;
AOR_CONST float kXeGtaoDefaultFalloffRange = 0.615f;
AOR_CONST float kXeGtaoDefaultSampleDistributionPower = 2.0f;
AOR_CONST float kXeGtaoDefaultThinOccluderCompensation = 0.0f;
AOR_CONST float kXeGtaoDefaultFinalValuePower = 2.2f;
AOR_CONST float kXeGtaoDefaultDepthMipSamplingOffset = 3.30f;

#include "../common/shared_end.h"
#endif
