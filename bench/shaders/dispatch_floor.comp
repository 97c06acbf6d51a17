#version 450
// One invocation per pixel doing nothing, one store, or one copy: the fixed cost under every pass.
#extension GL_GOOGLE_include_directive : require
#include "dispatch_floor.h"

layout(local_size_x_id = kFloorSpecWorkgroupSize, local_size_y_id = kFloorSpecWorkgroupSize) in;
layout(constant_id = kFloorSpecMode) const int kMode = kFloorModeNothing;
layout(push_constant) uniform Push { FloorConstants pc; };
layout(set = 0, binding = 0, rgba16f) uniform readonly image2D source;
layout(set = 0, binding = 1) uniform writeonly image2D target;  // any float format (shaderStorageImageWriteWithoutFormat)

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= pc.size.x || pixel.y >= pc.size.y) return;
  if (kMode == kFloorModeStore) imageStore(target, pixel, vec4(0.5f, 0.25f, 0.125f, 1.0f));
  if (kMode == kFloorModeCopy) imageStore(target, pixel, imageLoad(source, pixel));
}
