#version 450
// The SAO estimator, one thread per pixel: kSamples taps on a spiral rotated per pixel, each read
// from the CSZ level its distance selects; with the second layer a tap takes the larger
// obscurance of its two layers (centre and normal are layer 0's), as the deep G-buffer paper does.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "sao.h"

layout(local_size_x = kWorkgroupSize, local_size_y = kWorkgroupSize) in;
layout(constant_id = kSaoSpecSamples) const int kSamples = 19;
layout(constant_id = kSaoSpecDualLayer) const bool kDualLayer = false;
layout(constant_id = kSaoSpecWorldNormals) const bool kWorldNormals = true;

layout(push_constant, scalar) uniform Push { SaoConstants pc; };
layout(set = 0, binding = 0) uniform sampler2D csz;                      // every level; R layer 0, G layer 1
layout(set = 0, binding = 1, rgba16f) uniform readonly image2D normals;  // world space (captured) or view space (reconstructed)
layout(set = 0, binding = 2) uniform writeonly image2D aoOut;            // R16F visibility

vec3 viewPosition(ivec2 pixel, float z) {
  return viewPositionFromNdc(pixelToNdc(vec2(pixel), pc.invSize), z, pc.ndcToViewMul, pc.ndcToViewAdd);
}

float tapObscurance(ivec2 centre, vec3 c, vec3 n, float diskRadius, int i, float spin) {
  float unitRadius;
  vec2 direction = saoTapLocation(i, kSamples, pc.spiralTurns, spin, unitRadius);
  float ssR = unitRadius * diskRadius;
  ivec2 tap = centre + ivec2(ssR * direction);
  // Off-screen taps occlude nothing (the paper clamps to the edge, which invents geometry).
  if (any(lessThan(tap, ivec2(0))) || any(greaterThanEqual(tap, pc.size))) return 0.0;
  int mip = saoMipLevel(ssR, pc.maxMip);
  ivec2 texel = min(tap >> mip, textureSize(csz, mip) - ivec2(1));
  vec2 z = texelFetch(csz, texel, mip).rg;
  float obscurance = z.x > 0.0 ? saoTapObscurance(viewPosition(tap, z.x) - c, n, pc.invRadius2, pc.bias) : 0.0;
  if (kDualLayer && z.y > 0.0)
    obscurance = max(obscurance, saoTapObscurance(viewPosition(tap, z.y) - c, n, pc.invRadius2, pc.bias));
  return obscurance;
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= pc.size.x || pixel.y >= pc.size.y) return;
  float z = texelFetch(csz, pixel, 0).r;
  if (z <= 0.0) {  // sky
    imageStore(aoOut, pixel, vec4(1.0));
    return;
  }
  vec3 c = viewPosition(pixel, z);
  vec3 n = imageLoad(normals, pixel).xyz;
  if (kWorldNormals) n = mat3(pc.worldToView0.xyz, pc.worldToView1.xyz, pc.worldToView2.xyz) * n;
  n = normalize(n);
  float diskRadius = pc.projScale * pc.radius / z;
  float spin = saoPixelAngle(pixel) + pc.rotationOffset;
  float sum = 0.0;
  for (int i = 0; i < kSamples; ++i) sum += tapObscurance(pixel, c, n, diskRadius, i, spin);
  imageStore(aoOut, pixel, vec4(saoVisibility(sum, pc.intensityFactor)));
}
