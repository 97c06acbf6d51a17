#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "reconstruct_normals.h"

layout(local_size_x = kWorkgroupSize, local_size_y = kWorkgroupSize) in;
layout(push_constant, scalar) uniform Push { ReconstructNormalsConstants pc; };
layout(set = 0, binding = 0) uniform sampler2D viewDistance;
layout(set = 0, binding = 1) uniform writeonly image2D normalsOut;  // RGBA16F view-space normal

bool usable(ivec2 p) {
  return p.x >= 0 && p.y >= 0 && p.x < pc.size.x && p.y < pc.size.y && texelFetch(viewDistance, p, 0).r > 0.0;
}

vec3 viewPosition(ivec2 p) {
  return viewPositionFromNdc(pixelToNdc(vec2(p), pc.invSize), texelFetch(viewDistance, p, 0).r, pc.ndcToViewMul, pc.ndcToViewAdd);
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= pc.size.x || pixel.y >= pc.size.y) return;
  vec3 normal = vec3(0.0);
  if (usable(pixel)) {
    vec3 centre = viewPosition(pixel);
    ivec2 l = pixel - ivec2(1, 0), r = pixel + ivec2(1, 0), t = pixel - ivec2(0, 1), b = pixel + ivec2(0, 1);
    bool hasL = usable(l), hasR = usable(r), hasT = usable(t), hasB = usable(b);
    if ((hasL || hasR) && (hasT || hasB)) {
      vec3 dx = smallerDifference(centre, hasL ? viewPosition(l) : centre, hasR ? viewPosition(r) : centre, hasL, hasR);
      vec3 dy = smallerDifference(centre, hasT ? viewPosition(t) : centre, hasB ? viewPosition(b) : centre, hasT, hasB);
      vec3 n = cross(dy, dx);
      float len2 = dot(n, n);
      if (len2 > 0.0) {
        n *= inversesqrt(len2);
        normal = dot(n, centre) > 0.0 ? -n : n;  // face the camera
      }
    }
  }
  imageStore(normalsOut, pixel, vec4(normal, 0.0));
}
