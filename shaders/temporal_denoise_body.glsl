// Body of temporal_denoise_<format>.comp: each variant defines AOR_AO_FORMAT (the current AO
// image's format qualifier) and includes this; see spatial_columns_body.glsl for why.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "temporal_denoise.h"

layout(local_size_x = kWorkgroupSize, local_size_y = kWorkgroupSize) in;
layout(constant_id = kTemporalSpecBent) const bool kBent = true;
layout(constant_id = kTemporalSpecHistory) const bool kHasHistory = true;
layout(push_constant, scalar) uniform Push { TemporalConstants pc; };
layout(set = 0, binding = 0, AOR_AO_FORMAT) uniform readonly image2D aoCurrent;  // spatial (or GTAO) output
// Every image is read as a storage image (cheaper than a sampler on lavapipe) and the history's
// bilinear filter is done here: the same weights on every device, instead of each sampler's own
// sub-texel precision (8 bits on most GPUs).
layout(set = 0, binding = 1, r32f) uniform readonly image2D viewDistance;
layout(set = 0, binding = 2, AOR_AO_FORMAT) uniform readonly image2D aoHistory;  // previous output
layout(set = 0, binding = 3, r32f) uniform readonly image2D previousDistance;    // previous frame's linear distance
layout(set = 0, binding = 4) uniform writeonly image2D aoOut;

// Bilinear read at a continuous pixel position (texel centres at integers), clamped to the edge.
vec4 historyBilinear(vec2 position) {
  vec2 base = floor(position);
  vec2 f = position - base;
  ivec2 p0 = clamp(ivec2(base), ivec2(0), pc.size - 1);
  ivec2 p1 = clamp(ivec2(base) + 1, ivec2(0), pc.size - 1);
  vec4 top = mix(imageLoad(aoHistory, p0), imageLoad(aoHistory, ivec2(p1.x, p0.y)), f.x);
  vec4 bottom = mix(imageLoad(aoHistory, ivec2(p0.x, p1.y)), imageLoad(aoHistory, p1), f.x);
  return mix(top, bottom, f.y);
}

// The blended value of one pixel, or `current` where no history applies: sky, off-screen in the
// previous frame, or another surface there. It returns early, so that a GPU skips the history
// and neighbourhood reads of those pixels, and main() stores once (on lavapipe every imageStore
// in a shader costs a full store, whichever branch it is in).
vec4 temporalPixel(ivec2 pixel, vec4 current) {
  float dist = imageLoad(viewDistance, pixel).r;
  vec3 view = viewPositionFromNdc(pixelToNdc(vec2(pixel), pc.invSize), dist, pc.ndcToViewMul, pc.ndcToViewAdd);
  vec3 previousView = (pc.viewToPreviousView * vec4(view, 1.0)).xyz;
  float expected = -previousView.z;
  vec2 ndc = previousNdc(previousView, pc.previousProjection);
  vec2 uv = ndc * 0.5 + 0.5;
  bool onScreen = all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0)));  // layer 1, false for NaN
  if (!(dist > 0.0 && expected > 0.0 && onScreen)) return current;
  vec2 previousPixel = uv * vec2(pc.size) - 0.5;
  // Layer 2: the surface seen there last frame must be this one.
  ivec2 nearest = clamp(ivec2(round(previousPixel)), ivec2(0), pc.size - 1);
  if (!depthConsistent(expected, imageLoad(previousDistance, nearest).r, kTemporalDepthTolerance)) return current;

  vec4 history = historyBilinear(previousPixel);
  // Layer 3: clamp history AO into the current 3x3 neighbourhood (bent normals are not clamped).
  float currentAo = kBent ? current.w : current.r;
  float lo = currentAo, hi = currentAo;  // the centre is `current`, already loaded
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      if (dx == 0 && dy == 0) continue;
      ivec2 p = clamp(pixel + ivec2(dx, dy), ivec2(0), pc.size - 1);
      float v = kBent ? imageLoad(aoCurrent, p).w : imageLoad(aoCurrent, p).r;
      lo = min(lo, v);
      hi = max(hi, v);
    }
  float historyAo = kBent ? history.w : history.r;
  float ao = temporalBlendAo(currentAo, historyAo, lo, hi, pc.blend);
  if (!kBent) return vec4(ao);
  vec3 bent = mix(current.xyz, history.xyz, pc.blend);
  float len = length(bent);
  bent = (len > 1e-6 && !isinf(len)) ? bent / len : current.xyz;  // NaN/Inf history: keep the current
  return vec4(bent, ao);
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= pc.size.x || pixel.y >= pc.size.y) return;
  vec4 current = imageLoad(aoCurrent, pixel);
  // No history must leave the current value bit for bit.
  imageStore(aoOut, pixel, kHasHistory ? temporalPixel(pixel, current) : current);
}
