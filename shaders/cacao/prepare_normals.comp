#version 450
// CACAO prepare normals from depth (generate_normals=1, or a capture without normals):
// FFX_CACAO_Prepare{Native,Downsampled}Normals. Each thread reconstructs the view depth of a 4x4
// neighbourhood (full-resolution pixels native, every second one downsampled) and writes the
// normal of each of its 2x2 centre pixels into that pixel's layer, from the edge-weighted cross
// products of FFX_CACAO_CalculateNormal.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_control_flow_attributes : require
#include "cacao_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = kCacaoSpecDownsampled) const bool kDownsampled = false;
layout(set = 0, binding = 1) uniform sampler2D depthIn;
layout(set = 0, binding = 2, rgba8_snorm) uniform writeonly image2DArray normalsOut;  // RGBA8_SNORM

// FFX_CACAO_CalculateNormal: the sum of the four cross products of neighbour directions whose two
// sides are both not edges, plus a small bias towards the camera.
vec3 calculateNormal(vec4 edgesLRTB, vec3 centre, vec3 left, vec3 right, vec3 top, vec3 bottom) {
  vec4 accepted = vec4(edgesLRTB.x * edgesLRTB.z, edgesLRTB.z * edgesLRTB.y, edgesLRTB.y * edgesLRTB.w, edgesLRTB.w * edgesLRTB.x);
  left = normalize(left - centre);
  right = normalize(right - centre);
  top = normalize(top - centre);
  bottom = normalize(bottom - centre);
  vec3 normal = vec3(0.0, 0.0, -0.0005);
  normal += accepted.x * cross(left, top);
  normal += accepted.y * cross(top, right);
  normal += accepted.z * cross(right, bottom);
  normal += accepted.w * cross(bottom, left);
  return normalize(normal);
}

void main() {
  CacaoConstants c = cacaoLayers[0];
  ivec2 tid = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(vec2(tid), c.ssaoBufferDimensions))) return;
  int step = kDownsampled ? 2 : 1;
  ivec2 base = (kDownsampled ? 4 : 2) * tid;
  vec2 pixelSize = float(step) * c.outputBufferInverseDimensions;
  vec2 uv = (vec2(base) + 0.5) * c.outputBufferInverseDimensions;
  ivec2 size = textureSize(depthIn, 0);
  // d[a][b]: the depth of the pixel (a - 1, b - 1) steps from base, clamped at the edge. Native,
  // four gathers of 2x2 blocks at their corners (as FidelityFX's GatherRed, which it takes at
  // texel centres; at a corner rounding cannot move the footprint; 0.82 -> 1.0x of sixteen
  // texelFetch's time on lavapipe); downsampled, every second pixel.
  float d[4][4];
  if (!kDownsampled) {
    AOR_UNROLL for (int gy = 0; gy < 2; ++gy)
      AOR_UNROLL for (int gx = 0; gx < 2; ++gx) {
        vec4 g = textureGather(depthIn, vec2(base + 2 * ivec2(gx, gy)) / vec2(size));  // x (0,1), y (1,1), z (1,0), w (0,0)
        d[2 * gx][2 * gy + 1] = g.x;
        d[2 * gx + 1][2 * gy + 1] = g.y;
        d[2 * gx + 1][2 * gy] = g.z;
        d[2 * gx][2 * gy] = g.w;
      }
  } else {
    AOR_UNROLL for (int a = 0; a < 4; ++a)
      AOR_UNROLL for (int b = 0; b < 4; ++b) d[a][b] = texelFetch(depthIn, clamp(base + step * ivec2(a - 1, b - 1), ivec2(0), size - 1), 0).x;
  }
  // p[a][b]: that pixel in view space (FidelityFX's p_ab).
  vec3 p[4][4];
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) p[a][b] = cacaoNdcToView(c, uv + vec2(a - 1, b - 1) * pixelSize, cacaoViewDepth(c, d[a][b]));
  for (int layer = 0; layer < kCacaoLayers; ++layer) {
    int a = 1 + layer % 2, b = 1 + layer / 2;
    vec4 edges = cacaoCalculateEdges(p[a][b].z, p[a - 1][b].z, p[a + 1][b].z, p[a][b - 1].z, p[a][b + 1].z);
    vec3 n = calculateNormal(edges, p[a][b], p[a - 1][b], p[a + 1][b], p[a][b - 1], p[a][b + 1]);
    imageStore(normalsOut, ivec3(tid, layer), vec4(n, 1.0));
  }
}
