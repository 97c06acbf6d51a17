#ifndef AOR_TEMPORAL_DENOISE_H
#define AOR_TEMPORAL_DENOISE_H
// Pass 3 of seed 000: reprojection through the previous camera and EMA blend, with three rejection
// layers: (1) off-screen, (2) relative depth mismatch, (3) neighbourhood clamp of the history AO.
#include "../common/common.h"
#include "../common/shared_begin.h"

AOR_CONST int kTemporalSpecBent = 0;
AOR_CONST int kTemporalSpecHistory = 1;   // false on the first frame / after a reset: pass-through
// half_res=1: the current AO is at half resolution and this pass upsamples it (also run alone, as
// `upsample`, when there is no temporal pass).
AOR_CONST int kTemporalSpecHalfResolution = 2;
AOR_CONST float kTemporalDepthTolerance = 0.05f;  // seed 000: |expected - stored| / expected > 5%

struct TemporalConstants {
  mat4 viewToPreviousView;  // current view space -> previous view space
  vec4 previousProjection;  // previous P00, P11, P20, P21 (perspective, depth [0,1])
  vec2 ndcToViewMul;
  vec2 ndcToViewAdd;
  vec2 invSize;
  ivec2 size;
  float blend;              // history weight (seed 000 temporal_blend)
};

#ifdef __cplusplus
// The reprojection terms of a frame against the previous one (everything but `blend`): built once
// here for the temporal pass and for the metrics that judge which history it may reuse.
inline TemporalConstants temporalReprojection(const mat4& view, const mat4& projection, const mat4& previousView,
                                              const mat4& previousProjection, int width, int height) {
  TemporalConstants c{};
  c.viewToPreviousView = previousView * inverse(view);
  c.previousProjection = {previousProjection[0][0], previousProjection[1][1], previousProjection[2][0],
                          previousProjection[2][1]};
  c.ndcToViewMul = ndcToViewMulOf(projection);
  c.ndcToViewAdd = ndcToViewAddOf(projection);
  c.invSize = {1.0f / float(width), 1.0f / float(height)};
  c.size = {width, height};
  return c;
}
#endif

// Previous-frame NDC of a previous-view-space point.
AOR_FUNC vec2 previousNdc(vec3 previousView, vec4 previousProjection) {
  float w = -previousView.z;
  return vec2((previousProjection.x * previousView.x + previousProjection.z * previousView.z) / w,
              (previousProjection.y * previousView.y + previousProjection.w * previousView.z) / w);
}

AOR_FUNC bool depthConsistent(float expected, float stored, float tolerance) {
  return stored > 0.0f && abs(expected - stored) <= tolerance * expected;
}

// EMA blend of the AO with history clamped to the current neighbourhood [lo, hi]. History that is
// not a visibility (NaN, Inf, outside [0,1]: damage from an earlier frame) is dropped, so such a
// value leaves the history within one frame instead of spreading (clamp of NaN is undefined).
AOR_FUNC float temporalBlendAo(float currentAo, float historyAo, float lo, float hi, float blend) {
  bool usable = historyAo >= 0.0f && historyAo <= 1.0f;  // false for NaN
  return usable ? mix(currentAo, clamp(historyAo, lo, hi), blend) : currentAo;
}

// Weights of the four half-resolution texels around a full-resolution pixel, in the order
// (0,0), (1,0), (0,1), (1,1) from the texel at floor(pixel / 2). Texel t stands for pixel 2t (GTAO
// evaluated it there), so `fraction` is 0 or 0.5 per axis. Each bilinear weight is scaled by how
// well the texel's distance matches the pixel's (the spatial pass's edge weight), so AO does not
// bleed across depth edges. Where no texel lies on the pixel's surface (a feature thinner than
// two pixels) the plain bilinear weights are returned: some value must be given, and it is the
// neighbourhood's. Seed 001 upsamples with a 5x5 kernel; 2x2 is enough here because the 5x5 blur
// ran on the texels before.
AOR_FUNC vec4 upsampleWeights(vec2 fraction, float pixelDistance, vec4 texelDistances) {
  vec4 bilinear = vec4((1.0f - fraction.x) * (1.0f - fraction.y), fraction.x * (1.0f - fraction.y),
                       (1.0f - fraction.x) * fraction.y, fraction.x * fraction.y);
  vec4 similarity = vec4(depthEdgeWeight(pixelDistance, texelDistances.x), depthEdgeWeight(pixelDistance, texelDistances.y),
                         depthEdgeWeight(pixelDistance, texelDistances.z), depthEdgeWeight(pixelDistance, texelDistances.w));
  vec4 weights = bilinear * similarity;
  return weights.x + weights.y + weights.z + weights.w > 0.0f ? weights : bilinear;
}

#include "../common/shared_end.h"
#endif
