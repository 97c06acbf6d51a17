#ifndef AOR_TEMPORAL_DENOISE_H
#define AOR_TEMPORAL_DENOISE_H
// Pass 3 of seed 000: reprojection through the previous camera and EMA blend, with three rejection
// layers: (1) off-screen, (2) relative depth mismatch, (3) neighbourhood clamp of the history AO.
#include "common.h"
#include "shared_begin.h"

AOR_CONST int kTemporalSpecBent = 0;
AOR_CONST int kTemporalSpecHistory = 1;   // false on the first frame / after a reset: pass-through
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

#include "shared_end.h"
#endif
