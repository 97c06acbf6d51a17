// Seed 004's pre-pass: both layers' depth-attachment values to camera-space Z (linear distance,
// sky -1), one texel per pixel, written into level 0 of the CSZ pyramid (R16F/R32F, or RG with
// the second layer in G). Included by csz_single.comp and csz_dual.comp with SAO_DUAL_LAYER set:
// the single-layer shader has no second-layer binding at all.
#extension GL_EXT_scalar_block_layout : require
#include "../blocks/linearize_depth.h"
#include "sao.h"

layout(local_size_x = kWorkgroupSize, local_size_y = kWorkgroupSize) in;
layout(push_constant, scalar) uniform Push { SaoCszConstants pc; };
layout(set = 0, binding = 0, r32f) uniform readonly image2D depth0;  // layer 0 as captured
#if SAO_DUAL_LAYER
layout(set = 0, binding = 1, r32f) uniform readonly image2D depth1;  // layer 1 as captured
layout(set = 0, binding = 2) uniform writeonly image2D csz;          // level 0: RG
#else
layout(set = 0, binding = 1) uniform writeonly image2D csz;          // level 0: R
#endif

float cameraSpaceZ(float depth) {
  float d = linearViewDistance(depth, pc.projection22, pc.projection32, pc.reversedDepth != 0u);
  return d > pc.maxDistance ? kSkyDistance : d;
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= pc.size.x || pixel.y >= pc.size.y) return;
  float z0 = cameraSpaceZ(imageLoad(depth0, pixel).r);
#if SAO_DUAL_LAYER
  // Layer 1 exists only behind layer 0: where layer 0 is sky, so is layer 1.
  float z1 = z0 > 0.0 ? cameraSpaceZ(imageLoad(depth1, pixel).r) : kSkyDistance;
  imageStore(csz, pixel, vec4(z0, z1, 0.0, 0.0));
#else
  imageStore(csz, pixel, vec4(z0));
#endif
}
