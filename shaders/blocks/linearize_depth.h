#ifndef AOR_LINEARIZE_DEPTH_H
#define AOR_LINEARIZE_DEPTH_H
// Converts depth-attachment values to positive linear view distance once per frame, so the later
// passes never repeat the division (and reversed/standard handling lives in one place).
#include "../common/common.h"
#include "../common/shared_begin.h"

AOR_CONST uint kLinearizeWorkgroupSize = 16u;  // not 8x8: twice as fast on the H100, 20 % on lavapipe (shaders/README.md)

struct LinearizeConstants {
  ivec2 size;
  float projection22;  // P[2][2]
  float projection32;  // P[3][2]
  uint reversedDepth;  // 1: near = 1, far = 0
  uint pad0;
};

// Farther surfaces are treated as sky: the passes square view-space lengths (up to ~11 x distance
// at a 170 degree FOV), which must stay finite in float32 (sqrt(FLT_MAX) ~ 1.8e19).
AOR_CONST float kMaxViewDistance = 1e15f;

// distance = P32 / (d + P22) holds for standard and reversed, finite and infinite perspective
// projections with depth range [0,1]. Depth at or beyond the far value is sky; non-finite or
// out-of-range depth is invalid and treated as sky as well.
AOR_FUNC float linearViewDistance(float depth, float projection22, float projection32, bool reversedDepth) {
  bool finiteDepth = !isnan(depth) && !isinf(depth);
  bool beyondFar = reversedDepth ? depth <= 0.0f : depth >= 1.0f;
  bool outOfRange = depth < 0.0f || depth > 1.0f;
  if (!finiteDepth || beyondFar || outOfRange) return kSkyDistance;
  float dist = projection32 / (depth + projection22);
  return (dist > 0.0f && dist <= kMaxViewDistance) ? dist : kSkyDistance;  // also false for NaN and Inf
}

#include "../common/shared_end.h"
#endif
