#version 450
// Pass 1 of seed 000: horizon-search GTAO with bent normals, one thread per pixel, no shared memory.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_control_flow_attributes : require
#include "gtao.h"

layout(local_size_x = kGtaoWorkgroupSize, local_size_y = kGtaoWorkgroupSize) in;
layout(constant_id = kGtaoSpecSlices) const int kSlices = 3;
layout(constant_id = kGtaoSpecSteps) const int kSteps = 3;
layout(constant_id = kGtaoSpecBent) const bool kBent = true;
layout(constant_id = kGtaoSpecViewNormals) const bool kViewNormals = false;
layout(constant_id = kGtaoSpecThin) const bool kThin = false;
layout(constant_id = kGtaoSpecHalfResolution) const bool kHalfResolution = false;

layout(push_constant, scalar) uniform Push { GtaoConstants pc; };
layout(set = 0, binding = 0, r32f) uniform readonly image2D viewDistance;  // linear distance, sky <= 0 (storage read: cheaper than a sampler on lavapipe)
layout(set = 0, binding = 1, rgba16f) uniform readonly image2D normals;  // world (or view) space; storage read, as above
layout(set = 0, binding = 2) uniform writeonly image2D aoOut; // R16F visibility, or RGBA16F bent.xyz + visibility

float gtaoLoadDistance(ivec2 pixel) { return imageLoad(viewDistance, pixel).r; }

vec3 gtaoLoadViewNormal(ivec2 pixel) {
  vec3 n = imageLoad(normals, pixel).xyz;
  if (!kViewNormals) n = mat3(pc.worldToView0.xyz, pc.worldToView1.xyz, pc.worldToView2.xyz) * n;
  return n;
}

#include "gtao_pixel.glsl"

// At half resolution each thread evaluates the top-left pixel of a 2x2 block at full resolution
// (its samples still step over full-resolution pixels) and writes one texel; the upsample in the
// last pass treats texel t as pixel 2t. The noise follows the texel, not the pixel: interleaved
// gradient noise read at every other pixel varies by only 0.11 between neighbouring texels,
// which the 5x5 blur would not average out.
void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  int divisor = kHalfResolution ? 2 : 1;
  ivec2 outputSize = reducedSize(pc.size, divisor);
  if (texel.x >= outputSize.x || texel.y >= outputSize.y) return;
  vec3 bent;
  float visibility = gtaoPixelWithNoise(texel * divisor, gtaoNoise(texel, pc.frameIndex), bent);
  imageStore(aoOut, texel, kBent ? vec4(bent, visibility) : vec4(visibility));
}
