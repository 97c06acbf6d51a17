#ifndef AOR_COMMON_H
#define AOR_COMMON_H
// Constants and helpers every pass shares: workgroup size, view-space reconstruction, sky.
#include "shared_begin.h"

AOR_CONST uint kWorkgroupSize = 8u;  // 8x8 threads, one per pixel (seed 000)
AOR_CONST float kPi = 3.14159265358979f;
AOR_CONST float kHalfPi = 1.57079632679490f;

// Linear depth is the positive distance along -Z in view space. Pixels with no surface (sky, or
// invalid input such as NaN depth) are stored as kSkyDistance so every pass can test `d <= 0`.
AOR_CONST float kSkyDistance = -1.0f;

// For a perspective projection P (glm P[col][row]): view.xy = dist * (ndc.xy * mul + add) with
// mul = 1/(P00, P11) and add = (P20, P21)/(P00, P11); XeGTAO calls these NDCToViewMul/Add.
AOR_FUNC vec3 viewPositionFromNdc(vec2 ndc, float dist, vec2 ndcToViewMul, vec2 ndcToViewAdd) {
  return vec3(dist * (ndc.x * ndcToViewMul.x + ndcToViewAdd.x), dist * (ndc.y * ndcToViewMul.y + ndcToViewAdd.y), -dist);
}

#ifdef __cplusplus
// The two terms above, from P, for every pass constant that carries them.
inline vec2 ndcToViewMulOf(const mat4& p) { return {1.0f / p[0][0], 1.0f / p[1][1]}; }
inline vec2 ndcToViewAddOf(const mat4& p) { return {p[2][0] / p[0][0], p[2][1] / p[1][1]}; }
#endif

// Pixel (x, y), row 0 at the top, samples NDC ((2x+1)/W - 1, (2y+1)/H - 1) (capture format v1).
AOR_FUNC vec2 pixelToNdc(vec2 pixel, vec2 invSize) {
  return vec2((2.0f * pixel.x + 1.0f) * invSize.x - 1.0f, (2.0f * pixel.y + 1.0f) * invSize.y - 1.0f);
}

// Size of an image at 1/divisor of the frame's resolution: texel t stands for pixel divisor * t,
// so the last row and column of an odd size keep a texel of their own.
AOR_FUNC ivec2 reducedSize(ivec2 size, int divisor) { return (size + (divisor - 1)) / divisor; }

// Relative depth similarity used by the spatial edge weights (seed 000: 5% of the larger depth).
AOR_FUNC float depthEdgeWeight(float z1, float z2) {
  if (z1 <= 0.0f || z2 <= 0.0f) return (z1 <= 0.0f && z2 <= 0.0f) ? 1.0f : 0.0f;
  return clamp(1.0f - abs(z1 - z2) / (max(z1, z2) * 0.05f), 0.0f, 1.0f);
}

#include "shared_end.h"
#endif
