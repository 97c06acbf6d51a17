#version 450
// Not XeGTAO's: the engine's step XeGTAO leaves to it. After the last denoise pass, the pixels the
// shared front calls sky (blocks/linearize_depth.h: depth at or beyond the far value, NaN, out of
// range) get what XeGTAO's last pass would store for full visibility with the bent normal towards
// the viewer; every other pixel keeps XeGTAO's value (only sky pixels are written). A pass of its
// own so that XeGTAO's three passes stay XeGTAO's (README: "Sky and invalid depth").
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "horizon.h"

layout(local_size_x = kHorizonWorkgroupSize, local_size_y = kHorizonWorkgroupSize) in;
layout(constant_id = kHorizonSpecBent) const bool kBent = false;
layout(constant_id = kHorizonSpecReversedDepth) const bool kReversedDepth = false;
layout(push_constant, scalar) uniform Push { HorizonConstants pc; };
layout(set = 0, binding = 0) uniform sampler2D screenDepth;   // the capture's depth, nearest, clamped
layout(set = 0, binding = 1) uniform writeonly image2D outputAo;  // the last denoise pass's output, in place

#include "horizon_common.glsl"
#include "horizon_term.glsl"
#include "../blocks/linearize_depth.h"

// One pixel: if it is sky, what XeGTAO's last pass would store there for full visibility.
void storeIfSky(ivec2 pixel, float depth) {
  // depthUnpackConsts are (-P32, -P22): the front's distance P32 / (d + P22), bit for bit.
  if (any(greaterThanEqual(pixel, pc.viewportSize))) return;
  if (linearViewDistance(depth, -pc.depthUnpackConsts.y, -pc.depthUnpackConsts.x, kReversedDepth) > 0.0) return;  // not sky
  vec2 screenPos = (vec2(pixel) + 0.5) * pc.viewportPixelSize;
  vec4 term = vec4(-horizonViewPosition(screenPos, 1.0), 1.0 / kHorizonOcclusionTermScale);  // the view vector, unnormalised
  imageStore(outputAo, pixel, horizonEngineValue(term));
}

// A 2x2 quad a thread, its depths in one gather (as the prefilter reads them): a quarter of the
// invocations, which is most of this pass's cost on a CPU device.
void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy * 2u);
  vec4 quad = textureGatherOffset(screenDepth, vec2(pixel) * pc.viewportPixelSize, ivec2(1, 1));  // w, z, x, y = TL, TR, BL, BR
  storeIfSky(pixel, quad.w);
  storeIfSky(pixel + ivec2(1, 0), quad.z);
  storeIfSky(pixel + ivec2(0, 1), quad.x);
  storeIfSky(pixel + ivec2(1, 1), quad.y);
}
