// Body of temporal_denoise_<format>.comp: each variant defines AOR_AO_FORMAT (the current AO
// image's format qualifier) and includes this; see spatial_columns_body.glsl for why.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "temporal_denoise.h"

layout(local_size_x = kWorkgroupSize, local_size_y = kWorkgroupSize) in;
layout(constant_id = kTemporalSpecBent) const bool kBent = true;
layout(constant_id = kTemporalSpecHistory) const bool kHasHistory = true;
layout(constant_id = kTemporalSpecHalfResolution) const bool kHalfResolution = false;
layout(push_constant, scalar) uniform Push { TemporalConstants pc; };
layout(set = 0, binding = 0, AOR_AO_FORMAT) uniform readonly image2D aoCurrent;  // spatial (or GTAO) output; half size with kHalfResolution
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

float visibilityOf(vec4 ao) { return kBent ? ao.w : ao.r; }

// Visibility range of the current AO in the pixel's 3x3 neighbourhood (layer 3).
vec2 neighbourhoodRange(ivec2 pixel, float centre) {
  vec2 range = vec2(centre);  // the centre is `current`, already loaded
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      if (dx == 0 && dy == 0) continue;
      float v = visibilityOf(imageLoad(aoCurrent, clamp(pixel + ivec2(dx, dy), ivec2(0), pc.size - 1)));
      range = vec2(min(range.x, v), max(range.y, v));
    }
  return range;
}

// The half-resolution AO at a full-resolution pixel at distance `dist` (half_res=1), and through
// `range` the visibility range of the four texels it blends, which layer 3 clamps history to (they
// cover the pixel's 3x3 neighbourhood and more). A pixel GTAO evaluated (pixel 2t) gets its texel
// as is.
vec4 upsampledCurrent(ivec2 pixel, float dist, out vec2 range) {
  ivec2 base = pixel / 2;
  ivec2 last = reducedSize(pc.size, 2) - 1;
  vec4 texels[4];
  vec4 texelDistances;
  for (int i = 0; i < 4; ++i) {
    ivec2 texel = min(base + ivec2(i & 1, i >> 1), last);
    texels[i] = imageLoad(aoCurrent, texel);
    texelDistances[i] = imageLoad(viewDistance, texel * 2).r;
    float v = visibilityOf(texels[i]);
    range = i == 0 ? vec2(v) : vec2(min(range.x, v), max(range.y, v));
  }
  if (pixel == base * 2) return texels[0];
  if (!(dist > 0.0)) return kBent ? vec4(0.0, 0.0, 1.0, 1.0) : vec4(1.0);  // sky: what GTAO writes there
  vec4 w = upsampleWeights(vec2(pixel - base * 2) * 0.5, dist, texelDistances);
  vec4 result = (w.x * texels[0] + w.y * texels[1] + w.z * texels[2] + w.w * texels[3]) / (w.x + w.y + w.z + w.w);
  if (!kBent) return result;
  float len = length(result.xyz);  // unit normals blended: re-normalised, as the spatial pass does
  return vec4(len > 1e-6 ? result.xyz / len : texels[0].xyz, result.w);
}

// The blended value of one pixel, or `current` where no history applies: sky, off-screen in the
// previous frame, or another surface there. It returns early, so that a GPU skips the history
// and neighbourhood reads of those pixels, and main() stores once (on lavapipe every imageStore
// in a shader costs a full store, whichever branch it is in).
vec4 temporalPixel(ivec2 pixel, float dist, vec4 current, vec2 upsampledRange) {
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
  // Layer 3: clamp history AO into the current neighbourhood (bent normals are not clamped).
  float currentAo = visibilityOf(current);
  vec2 range = kHalfResolution ? upsampledRange : neighbourhoodRange(pixel, currentAo);
  float ao = temporalBlendAo(currentAo, visibilityOf(history), range.x, range.y, pc.blend);
  if (!kBent) return vec4(ao);
  vec3 bent = mix(current.xyz, history.xyz, pc.blend);
  float len = length(bent);
  bent = (len > 1e-6 && !isinf(len)) ? bent / len : current.xyz;  // NaN/Inf history: keep the current
  return vec4(bent, ao);
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= pc.size.x || pixel.y >= pc.size.y) return;
  float dist = imageLoad(viewDistance, pixel).r;  // read once, for the upsample and the reprojection
  vec2 upsampledRange = vec2(0.0);
  vec4 current = kHalfResolution ? upsampledCurrent(pixel, dist, upsampledRange) : imageLoad(aoCurrent, pixel);
  // No history must leave the current value bit for bit.
  imageStore(aoOut, pixel, kHasHistory ? temporalPixel(pixel, dist, current, upsampledRange) : current);
}
