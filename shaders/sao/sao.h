#ifndef AOR_SAO_H
#define AOR_SAO_H
// Seed 004 / Scalable Ambient Obscurance (McGuire, Mara, Luebke, HPG 2012), with the deep G-buffer
// paper's second layer (Mara, McGuire, Nowrouzezahrai, Luebke 2016): the passes' constants and the
// per-tap math, shared by the shaders (csz, minify, sao, blur) and the C++ that fills the constants.
#include "../common/common.h"
#include "../common/shared_begin.h"

// Specialisation constant ids of sao.comp.
AOR_CONST int kSaoSpecSamples = 0;    // taps per pixel: the loop's count
AOR_CONST int kSaoSpecDualLayer = 1;  // each tap also reads layer 1 (csz.g)
AOR_CONST int kSaoSpecWorldNormals = 2;  // the capture's world-space normals, rotated here (else view space)

// Camera-space Z pyramid: level 0 and four rotated-grid levels below it (the paper's 5 levels;
// deeper ones gain nothing at these radii, see sao/README.md).
AOR_CONST uint kSaoMipLevels = 5u;
AOR_CONST int kSaoMaxMip = 4;
// log2 of the tap distance in pixels up to which a tap reads level 0: beyond 2^3 = 8 pixels every
// doubling of the distance moves one level down (the paper's LOG_MAX_OFFSET).
AOR_CONST int kSaoLogMaxOffset = 3;
// The estimator's epsilon in the denominator (the paper's 0.01, world units squared).
AOR_CONST float kSaoEpsilon = 0.01f;
// The paper's normalisation of the falloff-weighted sum: 1 - 5 sigma / (r^6 s) * sum.
AOR_CONST float kSaoNormalisation = 5.0f;
// Largest distance a half float stores exactly enough (65504 is its largest finite value);
// farther surfaces are written as sky in the 16-bit CSZ.
AOR_CONST float kSaoMaxHalfDistance = 65000.0f;
// Bilateral key scale of the blur: the paper's 2000 per unit of z / 300 (its key is z over a
// nominal 300-unit far plane), so a tap 1 / (6.67 edge_sharpness) units off in depth weighs 0.
AOR_CONST float kSaoEdgeScale = 2000.0f / 300.0f;

struct SaoCszConstants {
  ivec2 size;
  float projection22;  // P[2][2]
  float projection32;  // P[3][2]
  uint reversedDepth;  // 1: near = 1, far = 0
  float maxDistance;   // beyond it a surface is stored as sky (kSaoMaxHalfDistance in 16 bits)
};

struct SaoMinifyConstants {
  ivec2 size;        // of the level written
  ivec2 sourceSize;  // of the level read
};

struct SaoConstants {
  vec4 worldToView0;      // columns of the world->view rotation, for the capture's normals
  vec4 worldToView1;
  vec4 worldToView2;
  vec2 ndcToViewMul;
  vec2 ndcToViewAdd;
  vec2 invSize;
  ivec2 size;
  float radius;           // world units
  float invRadius2;       // 1 / r^2
  float bias;             // beta, world units
  float intensityFactor;  // 5 sigma / s (the r^6 is in saoTapObscurance's falloff)
  float projScale;        // pixels covered by one unit at distance 1
  float spiralTurns;      // tau
  float rotationOffset;   // added to every pixel's rotation (frame-dependent only with temporal > 0)
  int maxMip;             // the pyramid's last level: kSaoMaxMip, less for a frame too small for it
};

struct SaoBlurConstants {
  ivec2 size;
  ivec2 axis;            // (1, 0) horizontal, (0, 1) vertical
  int radius;            // taps on each side
  int step;              // pixels between taps
  float sigma;           // of the Gaussian, in taps
  float edgeSharpness;
};

// The paper's per-pixel rotation of the spiral (a hash from Alchemy AO), in radians:
// (3x ^ y + xy) * 10, grouped as C and GLSL group it (+ binds tighter than ^).
AOR_FUNC float saoPixelAngle(ivec2 pixel) {
  return float((3 * pixel.x) ^ (pixel.y + pixel.x * pixel.y)) * 10.0f;
}

// Tap i of s on the unit disk: radius alpha = (i + 0.5) / s, angle alpha * tau turns + spin.
AOR_FUNC vec2 saoTapLocation(int i, int samples, float spiralTurns, float spin, AOR_OUT(float) unitRadius) {
  float alpha = (float(i) + 0.5f) / float(samples);
  float angle = alpha * (spiralTurns * 2.0f * kPi) + spin;
  unitRadius = alpha;
  return vec2(cos(angle), sin(angle));
}

// The level a tap ssR pixels from the centre reads: floor(log2 ssR) - 3, clamped to the pyramid.
AOR_FUNC int saoMipLevel(float ssR, int maxMip) {
  int whole = int(ssR);
  int log2Floor = whole > 0 ? findMSB(whole) : 0;
  return clamp(log2Floor - kSaoLogMaxOffset, 0, maxMip);
}

// Rotated-grid subsampling: the texel of level m that texel t of level m + 1 keeps (no averaging:
// one real depth, alternating the offset by row and column so neither axis is favoured).
AOR_FUNC ivec2 saoRotatedGridSource(ivec2 t, ivec2 sourceSize) {
  ivec2 s = ivec2(2 * t.x + ((t.y & 1) ^ 1), 2 * t.y + ((t.x & 1) ^ 1));
  return min(s, sourceSize - ivec2(1));
}

// One tap's obscurance: v from the centre to the tap, n the centre's unit normal. The paper's
// falloff (r^2 - v.v)^3 / r^6, written as (1 - v.v / r^2)^3 so that no power of the radius is
// formed (r^6 overflows a float from r ~ 2.6e6), and its bias: max(0, (v.n - beta) / (v.v + epsilon)).
AOR_FUNC float saoTapObscurance(vec3 v, vec3 n, float invRadius2, float bias) {
  float vv = dot(v, v);
  float vn = dot(v, n);
  float f = max(1.0f - vv * invRadius2, 0.0f);
  return f * f * f * max((vn - bias) / (kSaoEpsilon + vv), 0.0f);
}

// Visibility from the sum of the taps' obscurance.
AOR_FUNC float saoVisibility(float sum, float intensityFactor) {
  return max(0.0f, 1.0f - sum * intensityFactor);
}

// The blur's weight of a tap r taps from the centre, |dz| units away in depth.
AOR_FUNC float saoBlurWeight(int r, float sigma, float dz, float edgeSharpness) {
  float gaussian = exp(-float(r * r) / (2.0f * sigma * sigma));
  return gaussian * max(0.0f, 1.0f - edgeSharpness * kSaoEdgeScale * abs(dz));
}

#include "../common/shared_end.h"
#endif
