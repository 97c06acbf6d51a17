#version 450
// Screen-space reference (`--technique reference`): the GTAO integral of gtao_pixel.glsl evaluated
// exhaustively on the depth buffer: kSlices evenly spaced directions with no noise, and on each
// side every pixel the slice line crosses out to the AO radius (one sample per pixel column or
// row, whichever the direction crosses faster). Same horizon test, falloff, thin heuristic,
// normalisation and power as `gtao`; nothing is denoised. Its error against the ray-traced
// reference is the screen-space assumption's alone; GTAO's error against it is sampling's.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "gtao.h"

layout(local_size_x = kWorkgroupSize, local_size_y = kWorkgroupSize) in;
layout(constant_id = kGtaoSpecSlices) const int kSlices = 32;
layout(constant_id = kGtaoSpecBent) const bool kBent = true;
layout(constant_id = kGtaoSpecViewNormals) const bool kViewNormals = false;
const int kSteps = 1;  // gtaoPixel (unused here) needs it

layout(push_constant, scalar) uniform Push { GtaoConstants pc; };
layout(set = 0, binding = 0) uniform sampler2D viewDistance;  // R32F linear distance, sky <= 0
layout(set = 0, binding = 1) uniform sampler2D normals;       // RGBA16F, world (or view) space
layout(set = 0, binding = 2) uniform writeonly image2D aoOut; // R16F visibility, or RGBA16F bent.xyz + visibility

float gtaoLoadDistance(ivec2 pixel) { return texelFetch(viewDistance, pixel, 0).r; }

vec3 gtaoLoadViewNormal(ivec2 pixel) {
  vec3 n = texelFetch(normals, pixel, 0).xyz;
  if (!kViewNormals) n = mat3(pc.worldToView0.xyz, pc.worldToView1.xyz, pc.worldToView2.xyz) * n;
  float len2 = dot(n, n);
  return len2 > 1e-12 ? n * inversesqrt(len2) : vec3(0.0);
}

#include "gtao_pixel.glsl"

float referencePixel(ivec2 pixel, out vec3 bentNormal) {
  bentNormal = vec3(0.0, 0.0, 1.0);
  float dist = gtaoLoadDistance(pixel);
  if (dist <= 0.0) return 1.0;

  vec3 centre = gtaoViewPosition(pixel, dist);
  vec3 viewDir = normalize(-centre);
  vec3 normal = gtaoLoadViewNormal(pixel);
  if (!(dot(normal, normal) > 1e-12)) normal = viewDir;

  float screenRadius = min(pc.radius * pc.pixelsPerUnit / dist, length(vec2(pc.size)));
  float visibility = 0.0;
  float unoccluded = 0.0;
  vec3 bentSum = vec3(0.0);
  for (int slice = 0; slice < kSlices; ++slice) {
    float phi = (float(slice) + 0.5) * (kPi / float(kSlices));
    vec2 omega = vec2(cos(phi), sin(phi));
    vec3 direction = normalize(vec3(omega.x * pc.viewPerPixel.x, omega.y * pc.viewPerPixel.y, 0.0));
    // Slice frame exactly as gtaoPixel builds it (n from atan: precise for surfaces facing us).
    vec3 orthoDirection = normalize(direction - dot(direction, viewDir) * viewDir);
    vec3 axis = normalize(cross(direction, viewDir));
    vec3 projectedNormal = normal - axis * dot(normal, axis);
    float projectedLength = length(projectedNormal);
    if (!(projectedLength > 1e-6)) continue;

    float normalAlong = dot(projectedNormal, viewDir);
    float normalAcross = dot(projectedNormal, orthoDirection);
    float signN = normalAcross >= 0.0 ? 1.0 : -1.0;
    bool facesViewer = normalAlong > 0.0;
    float cosN = facesViewer ? clamp(normalAlong / projectedLength, 0.0, 1.0) : 0.0;
    float n = facesViewer ? signN * atan(abs(normalAcross), normalAlong) : signN * kHalfPi;
    float sinN = facesViewer ? clamp(normalAcross / projectedLength, -1.0, 1.0) : signN;
    float lowCosPos = -sinN;  // cos(n + pi/2)
    float lowCosNeg = sinN;   // cos(n - pi/2)
    float horizonCosPos = lowCosPos;
    float horizonCosNeg = lowCosNeg;

    // One sample per crossed pixel: advance one pixel along the major axis per step.
    vec2 step = omega / max(abs(omega.x), abs(omega.y));
    int count = int(screenRadius / length(step)) + 1;
    for (int k = 1; k <= count; ++k) {
      ivec2 offset = ivec2(round(step * float(k)));
      horizonCosPos = max(horizonCosPos, gtaoSampleHorizonCos(pixel + offset, centre, normal, projectedLength, cosN, sinN, 1.0, lowCosPos));
      horizonCosNeg = max(horizonCosNeg, gtaoSampleHorizonCos(pixel - offset, centre, normal, projectedLength, cosN, sinN, -1.0, lowCosNeg));
    }

    float hPos = n + clamp(safeAcos(horizonCosPos) - n, -kHalfPi, kHalfPi);
    float hNeg = n + clamp(-safeAcos(horizonCosNeg) - n, -kHalfPi, kHalfPi);
    visibility += projectedLength * gtaoSliceVisibility(hPos, -hNeg, n);
    unoccluded += projectedLength * gtaoUnoccludedSlice(n, cosN, sinN);
    if (kBent) {
      vec2 b = gtaoSliceBentNormal(hNeg, hPos, n);
      bentSum += rotateZTo(viewDir, vec3(direction.x * b.x, direction.y * b.x, b.y)) * projectedLength;
    }
  }
  visibility = unoccluded > 0.0 ? clamp(visibility / unoccluded, 0.0, 1.0) : 1.0;
  if (pc.power != 1.0) visibility = pow(visibility, pc.power);
  if (kBent) {
    float bentLength = length(bentSum);
    bentNormal = bentLength > 1e-6 ? bentSum / bentLength : normal;
  }
  return visibility;
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= pc.size.x || pixel.y >= pc.size.y) return;
  vec3 bent;
  float visibility = referencePixel(pixel, bent);
  imageStore(aoOut, pixel, kBent ? vec4(bent, visibility) : vec4(visibility));
}
