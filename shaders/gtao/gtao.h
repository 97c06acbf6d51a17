#ifndef AOR_GTAO_H
#define AOR_GTAO_H
// GTAO main pass (seed 000, pass 1): constants, defaults and the closed-form math, shared by
// gtao.comp and the CPU mirror (replay/cpu/gtao_cpu.cpp). The per-pixel horizon search that needs
// depth fetches lives in gtao_pixel.glsl.
#include "../common/common.h"
#include "../common/shared_begin.h"

// Specialisation constant ids: slices/steps fix the loop counts; bent normals and the normal source
// are compiled out when unused (issue: build only what a run needs).
AOR_CONST int kGtaoSpecSlices = 0;
AOR_CONST int kGtaoSpecSteps = 1;
AOR_CONST int kGtaoSpecBent = 2;
AOR_CONST int kGtaoSpecViewNormals = 3;
AOR_CONST int kGtaoSpecThin = 4;  // thin-occluder heuristic on (thin > 0): one more square root per sample
AOR_CONST int kGtaoSpecHalfResolution = 5;  // half_res=1: one output texel per 2x2 pixels (see gtao.comp)

AOR_CONST float kGtaoFalloffRange = 0.615f;      // seed 000 / XeGTAO: flat inner, linear outer 61.5%
AOR_CONST float kGoldenRatioFraction = 0.61803398875f;
AOR_CONST uint kNoisePeriodFrames = 64u;         // seed 000: frame_index % 64
AOR_CONST float kMinSampleOffsetPixels = 1.3f;   // first sample must leave the centre pixel
// Largest slices x steps whose slice loop is unrolled (every preset, ultra's 9x3 included).
AOR_CONST int kGtaoMaxUnrolledSliceSteps = 36;
AOR_CONST uint kGtaoWorkgroupSize = 16u;  // not the seed's 8x8: 8 % faster on the H100 at 4K (shaders/README.md)

struct GtaoConstants {
  vec4 worldToView0;   // columns of the world->view rotation (normals are world space in captures)
  vec4 worldToView1;
  vec4 worldToView2;
  vec2 ndcToViewMul;
  vec2 ndcToViewAdd;
  vec2 invSize;
  ivec2 size;
  float radius;          // world/view units
  float pixelsPerUnit;   // screen-space pixels covered by one view unit at distance 1
  float falloffRange;    // fraction of the radius over which weight fades (0 = hard cut-off)
  float thin;            // thin-occluder compensation (0 = off)
  float power;           // final exponent on visibility
  uint frameIndex;       // index of the frame in the capture (noise depends on it, nothing else)
  vec2 viewPerPixel;     // view-space xy step per pixel at distance 1 (signs follow the projection)
};

// Interleaved gradient noise (Jimenez 2014).
AOR_FUNC float interleavedGradientNoise(vec2 pixel) {
  return fract(52.9829189f * fract(0.06711056f * pixel.x + 0.00583715f * pixel.y));
}

// seed 000: base = fract(IGN(pixel) + (frame % 64) * phi); directions use base, steps a decorrelated copy.
AOR_FUNC vec2 gtaoNoise(ivec2 pixel, uint frameIndex) {
  float base = fract(interleavedGradientNoise(vec2(pixel)) + float(frameIndex % kNoisePeriodFrames) * kGoldenRatioFraction);
  return vec2(base, fract(base * 0.7f + 0.15f));
}

// Weight of a horizon sample at view-space distance `dist`: 1 inside radius*(1-falloffRange),
// fading linearly to 0 at the radius over the fade width. falloffRange = 0 gives a hard cut-off
// at the radius. The shader passes 1 / gtaoFadeWidth, computed once per pixel.
AOR_FUNC float gtaoFadeWidth(float radius, float falloffRange) {
  return max(falloffRange * radius, 1e-6f * radius);
}

AOR_FUNC float gtaoFalloffWeight(float dist, float radius, float invFadeWidth) {
  return clamp((radius - dist) * invFadeWidth, 0.0f, 1.0f);
}

// Cosine-weighted visibility of one side of a slice (GTAO paper eq. 10, seed 000 inner_integral).
AOR_FUNC float gtaoInnerIntegral(float h, float n) {
  return 0.25f * (-cos(2.0f * h - n) + cos(n) + 2.0f * h * sin(n));
}

// Both sides: h1 is the horizon angle on the +direction side, h2 on the -direction side, both
// measured from the view vector and positive; n is the projected normal's angle.
AOR_FUNC float gtaoSliceVisibility(float h1, float h2, float n) {
  return gtaoInnerIntegral(h1, n) + gtaoInnerIntegral(h2, -n);
}

// Horizon cosine of the tangent plane on one side of a slice (side +1: cos(n + pi/2) = -sin n;
// side -1: cos(n - pi/2) = sin n): where every horizon search starts, and what a sample that
// occludes nothing contributes.
AOR_FUNC float gtaoTangentHorizonCos(float sinN, float side) {
  return -side * sinN;
}

// The slice visibility with both horizons on the tangent plane (h = n +- pi/2): cos n + n sin n.
// Its average over all slice directions is exactly 1.
AOR_FUNC float gtaoUnoccludedSlice(float n, float cosN, float sinN) {
  return cosN + n * sinN;
}

// Bent normal of one slice (GTAO paper, Algorithm 2), in slice coordinates: x along the slice
// direction, z toward the viewer. hNeg <= n <= hPos are signed horizon angles.
AOR_FUNC vec2 gtaoSliceBentNormal(float hNeg, float hPos, float n) {
  float t0 = (6.0f * sin(hNeg - n) - sin(3.0f * hNeg - n) + 6.0f * sin(hPos - n) - sin(3.0f * hPos - n)
              + 16.0f * sin(n) - 3.0f * (sin(hNeg + n) + sin(hPos + n))) / 12.0f;
  float t1 = (-cos(3.0f * hNeg - n) - cos(3.0f * hPos - n) + 8.0f * cos(n)
              - 3.0f * (cos(hNeg + n) + cos(hPos + n))) / 12.0f;
  return vec2(t0, t1);
}

// The two slice integrals above, rewritten with angle-sum and triple-angle identities so they need
// only sin/cos of each horizon angle and of n, which the horizon search already has (the horizon
// cosine, and sin = +-sqrt(1 - cos^2)): no sin/cos call per slice instead of 18 (these were most
// of the GTAO pass's cost). Same values up to rounding; hNeg <= n <= hPos, signed as above.
// One horizon's share of gtaoSliceVisibility: 0.25 (-cos(2h - n) + cos n + 2 h sin n).
AOR_FUNC float gtaoHorizonVisibility(float h, float cosH, float sinH, float cosN, float sinN) {
  float cos2H = cosH * cosH - sinH * sinH;
  float sin2H = 2.0f * sinH * cosH;
  return 0.25f * (-(cos2H * cosN + sin2H * sinN) + cosN + 2.0f * h * sinN);
}

// One horizon's share of gtaoSliceBentNormal, before adding (16 sin n, 8 cos n) and dividing by 12.
AOR_FUNC vec2 gtaoHorizonBentTerms(float cosH, float sinH, float cosN, float sinN) {
  float sin3H = sinH * (3.0f - 4.0f * sinH * sinH);
  float cos3H = cosH * (4.0f * cosH * cosH - 3.0f);
  float sinHMinusN = sinH * cosN - cosH * sinN;
  float sinHPlusN = sinH * cosN + cosH * sinN;
  float cosHPlusN = cosH * cosN - sinH * sinN;
  float sin3HMinusN = sin3H * cosN - cos3H * sinN;
  float cos3HMinusN = cos3H * cosN + sin3H * sinN;
  return vec2(6.0f * sinHMinusN - sin3HMinusN - 3.0f * sinHPlusN, -cos3HMinusN - 3.0f * cosHPlusN);
}

// Rotation taking +Z (toward the viewer in slice space) onto v (Rodrigues, v not equal to -Z).
AOR_FUNC vec3 rotateZTo(vec3 v, vec3 x) {
  vec3 axis = vec3(-v.y, v.x, 0.0f);  // cross((0,0,1), v)
  float c = v.z;
  float h = 1.0f / (1.0f + c);
  return x * c + cross(axis, x) + axis * (dot(axis, x) * h);
}

#include "../common/shared_end.h"
#endif
