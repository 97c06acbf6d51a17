#ifndef AOR_HORIZON_H
#define AOR_HORIZON_H
// What the horizon-search techniques (xegtao, vbao) share, ported from XeGTAO (seed 002): the
// constants their passes read (XeGTAO.h's GTAOConstants, in the same order and at the same
// offsets, plus the two axis signs this tool needs to hand it view-space normals), the depth MIP
// chain's, denoiser's and sky pass's constants, and the spatio-temporal noise; shared by the
// shaders and C++. Where each value comes from in XeGTAO: replay/techniques/xegtao/README.md.
#include "../common/shared_begin.h"

// Specialisation constant ids the shared passes read (a technique's main pass takes its own ids
// from 0 up, skipping these).
AOR_CONST int kHorizonSpecBent = 2;           // XE_GTAO_COMPUTE_BENT_NORMALS
AOR_CONST int kHorizonSpecDepth32 = 4;        // XE_GTAO_FP32_DEPTHS: the centre pull-in of 32-bit depths
AOR_CONST int kHorizonSpecReversedDepth = 6;  // the sky pass: the capture's depth convention

AOR_CONST int kHorizonDepthMipLevels = 5;         // XE_GTAO_DEPTH_MIP_LEVELS
AOR_CONST uint kHorizonWorkgroupSize = 8u;        // XE_GTAO_NUMTHREADS_X/Y (the prefilter: 8x8 threads, 2x2 pixels each, 16x16 a group)
AOR_CONST float kHorizonOcclusionTermScale = 1.5f;  // XE_GTAO_OCCLUSION_TERM_SCALE
AOR_CONST float kHorizonDepth16PullIn = 0.99920f;   // centre depth moved towards the camera, R16F chain
AOR_CONST float kHorizonDepth32PullIn = 0.99999f;   // the same, R32F chain
AOR_CONST float kHorizonMaxDepth = 65504.0f;        // XeGTAO_ClampDepth's upper bound (see README: always fp16's)
AOR_CONST float kHorizonPixelTooClose = 1.3f;       // pixelTooCloseThreshold
AOR_CONST float kHorizonVisibilityFloor = 0.03f;
AOR_CONST float kHorizonEdgeSensitivity = 0.011f;   // XeGTAO_CalculateEdges: |dz| against 1.1 % of z
AOR_CONST float kHorizonDenoiseBlurBeta = 1.2f;     // DenoiseBlurBeta with denoising on
AOR_CONST float kHorizonDiagonalWeight = 0.425f;    // 0.85 * 0.5
AOR_CONST uint kHorizonNoisePeriod = 64u;           // NoiseIndex = frame % 64
AOR_CONST uint kHorizonNoiseFrameStride = 288u;     // Hilbert index offset per noise frame

// GTAOConstants, member for member (96 bytes, no member straddling 16 bytes: the same offsets under
// HLSL cbuffer packing and scalar layout), then the axis signs.
struct HorizonConstants {
  ivec2 viewportSize;
  vec2 viewportPixelSize;
  vec2 depthUnpackConsts;      // view z = x / (y - depth)
  vec2 cameraTanHalfFov;
  vec2 ndcToViewMul;           // XeGTAO's view space (x right, y up, z forward) from [0,1] screen uv
  vec2 ndcToViewAdd;
  vec2 ndcToViewMulXPixelSize;
  float effectRadius;
  float effectFalloffRange;
  float radiusMultiplier;
  float padding0;
  float finalValuePower;
  float denoiseBlurBeta;
  float sampleDistributionPower;
  float thinOccluderCompensation;
  float depthMipSamplingOffset;
  int noiseIndex;
  // Not XeGTAO's: signs taking this tool's view space (-z forward, the capture's axes) to XeGTAO's
  // for x and y (z always flips). Normals are turned by them on input, bent normals on output.
  vec2 viewAxisSigns;
};

// XeGTAO.h HilbertIndex: index of (x, y) along the Hilbert curve filling a 64x64 tile.
AOR_FUNC uint horizonHilbertIndex(uint x, uint y) {
  uint index = 0u;
  for (uint level = 32u; level > 0u; level /= 2u) {
    uint rx = (x & level) > 0u ? 1u : 0u;
    uint ry = (y & level) > 0u ? 1u : 0u;
    index += level * level * ((3u * rx) ^ ry);
    if (ry == 0u) {
      if (rx == 1u) {
        x = 63u - x;
        y = 63u - y;
      }
      uint swap = x;
      x = y;
      y = swap;
    }
  }
  return index;
}

// vaGTAO.hlsl SpatioTemporalNoise: the Hilbert index (offset 288 per noise frame) into the R2
// sequence. x drives the slice angle, y the step positions. The index wraps in uint32 as XeGTAO's.
AOR_FUNC vec2 horizonNoise(uvec2 pixel, uint noiseIndex) {
  uint index = horizonHilbertIndex(pixel.x, pixel.y) + kHorizonNoiseFrameStride * (noiseIndex % kHorizonNoisePeriod);
  return fract(vec2(0.5f) + float(index) * vec2(0.75487766624669276005f, 0.5698402909980532659114f));
}

#include "../common/shared_end.h"
#endif
