#version 450
// User techniques' `linear_depth` input: the front's linear view distance with sky (kSkyDistance,
// -1) as 0, as user_techniques/FORMAT.md promises.
#extension GL_GOOGLE_include_directive : require
#include "../common/common.h"

layout(local_size_x = kWorkgroupSize, local_size_y = kWorkgroupSize) in;
layout(set = 0, binding = 0, r32f) uniform readonly image2D distanceIn;
layout(set = 0, binding = 1, r32f) uniform writeonly image2D linearDepthOut;

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, imageSize(distanceIn)))) return;
  imageStore(linearDepthOut, pixel, vec4(max(imageLoad(distanceIn, pixel).r, 0.0)));
}
