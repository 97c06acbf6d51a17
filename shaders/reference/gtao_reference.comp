#version 450
// Screen-space reference (`--technique reference`): the GTAO integral of gtao_pixel.glsl evaluated
// exhaustively on the depth buffer: kSlices evenly spaced directions with no noise, and on each
// side every pixel the slice line crosses out to the AO radius (one sample per pixel column or
// row, whichever the direction crosses faster). Same horizon test, falloff, thin heuristic,
// normalisation and power as `gtao`; nothing is denoised. Its error against the ray-traced
// reference is the screen-space assumption's alone; GTAO's error against it is sampling's.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_control_flow_attributes : require
#include "../gtao/gtao.h"

layout(local_size_x = kWorkgroupSize, local_size_y = kWorkgroupSize) in;
layout(constant_id = kGtaoSpecSlices) const int kSlices = 32;
layout(constant_id = kGtaoSpecBent) const bool kBent = true;
layout(constant_id = kGtaoSpecViewNormals) const bool kViewNormals = false;
layout(constant_id = kGtaoSpecThin) const bool kThin = false;
const int kSteps = 1;  // gtaoPixel (unused here) needs it

layout(push_constant, scalar) uniform Push { GtaoConstants pc; };
layout(set = 0, binding = 0) uniform sampler2D viewDistance;  // R32F linear distance, sky <= 0
layout(set = 0, binding = 1) uniform sampler2D normals;       // RGBA16F, world (or view) space
layout(set = 0, binding = 2) uniform writeonly image2D aoOut; // R16F visibility, or RGBA16F bent.xyz + visibility

float gtaoLoadDistance(ivec2 pixel) { return texelFetch(viewDistance, pixel, 0).r; }

vec3 gtaoLoadViewNormal(ivec2 pixel) {
  vec3 n = texelFetch(normals, pixel, 0).xyz;
  if (!kViewNormals) n = mat3(pc.worldToView0.xyz, pc.worldToView1.xyz, pc.worldToView2.xyz) * n;
  return n;
}

#include "../gtao/gtao_pixel.glsl"

float referencePixel(ivec2 pixel, out vec3 bentNormal) {
  bentNormal = vec3(0.0, 0.0, 1.0);
  GtaoCentre c;
  if (!gtaoPixelCentre(pixel, c)) return 1.0;

  float visibility = 0.0;
  float unoccluded = 0.0;
  vec3 bentSum = vec3(0.0);
  for (int sliceIndex = 0; sliceIndex < kSlices; ++sliceIndex) {
    float phi = (float(sliceIndex) + 0.5) * (kPi / float(kSlices));  // evenly spaced, no noise
    vec2 omega = vec2(cos(phi), sin(phi));
    GtaoSlice slice;
    if (!gtaoSliceFrame(omega, c.viewDir, c.normal, slice)) continue;
    float horizonCosPos = gtaoTangentHorizonCos(slice.sinN, 1.0);
    float horizonCosNeg = gtaoTangentHorizonCos(slice.sinN, -1.0);
    // One sample per crossed pixel: advance one pixel along the major axis per step.
    vec2 step = omega / max(abs(omega.x), abs(omega.y));
    int count = int(c.screenRadius / length(step)) + 1;
    for (int k = 1; k <= count; ++k) {
      gtaoSampleBothSides(pixel, ivec2(round(step * float(k))), c, slice, horizonCosPos, horizonCosNeg);
    }
    gtaoAccumulateSlice(slice, horizonCosPos, horizonCosNeg, visibility, unoccluded, bentSum);
  }
  return gtaoResolve(visibility, unoccluded, bentSum, c.viewDir, c.normal, bentNormal);
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= pc.size.x || pixel.y >= pc.size.y) return;
  vec3 bent;
  float visibility = referencePixel(pixel, bent);
  imageStore(aoOut, pixel, kBent ? vec4(bent, visibility) : vec4(visibility));
}
