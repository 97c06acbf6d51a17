#version 450
// Shared front: world-space normals of the capture rotated to view space (FrameBuilder::viewNormals).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "view_normals.h"

layout(local_size_x = 16, local_size_y = 16) in;
layout(push_constant, scalar) uniform Push { ViewNormalsConstants pc; };
layout(set = 0, binding = 0, rgba16f) uniform readonly image2D worldNormals;
layout(set = 0, binding = 1, rgba16f) uniform writeonly image2D viewNormalsOut;

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= pc.size.x || pixel.y >= pc.size.y) return;
  vec3 n = viewSpaceNormal(imageLoad(worldNormals, pixel).xyz, pc.worldToView0.xyz, pc.worldToView1.xyz, pc.worldToView2.xyz);
  imageStore(viewNormalsOut, pixel, vec4(n, 0.0));
}
