// XeGTAO pass 2 (XeGTAO_MainPass with vaGTAO.hlsl's noise and normal loading), one thread per
// pixel in 8x8 workgroups. Built twice: main_pass.comp, and main_pass_taps.comp (XEGTAO_COUNT_TAPS)
// which also counts the depth taps by the MIP level the sampler reads (--debug mip_taps).
#include "xegtao.h"

layout(local_size_x = kHorizonWorkgroupSize, local_size_y = kHorizonWorkgroupSize) in;
layout(constant_id = kXeGtaoSpecSlices) const int kSlices = 3;
layout(constant_id = kXeGtaoSpecSteps) const int kSteps = 3;
layout(constant_id = kHorizonSpecBent) const bool kBent = false;
layout(constant_id = kXeGtaoSpecThin) const bool kThin = false;
layout(constant_id = kHorizonSpecDepth32) const bool kDepth32 = false;
layout(constant_id = kXeGtaoSpecSampleDistributionPower) const float kSampleDistributionPower = 2.0;

layout(push_constant, scalar) uniform Push { HorizonConstants pc; };
layout(set = 0, binding = 0) uniform sampler2D depthMips;   // pass 1's chain, nearest (texels and levels), clamped
layout(set = 0, binding = 1, rgba16f) uniform readonly image2D viewNormals;  // the front's, this tool's view space
layout(set = 0, binding = 2) uniform writeonly uimage2D workingAoTerm;       // R8_UINT (R32_UINT with bent normals)
layout(set = 0, binding = 3) uniform writeonly image2D workingEdges;         // R8_UNORM
#ifdef XEGTAO_COUNT_TAPS
layout(set = 0, binding = 4, std430) buffer MipTaps { uint mipTaps[kHorizonDepthMipLevels]; };
shared uint groupTaps[kHorizonDepthMipLevels];
#endif

#include "horizon/horizon_common.glsl"

#ifdef XEGTAO_COUNT_TAPS
bool countingThread = false;  // a thread of a pixel in the frame (not one past its edge)
// The level a nearest-mipmap sampler reads for `lod` (rounded to nearest, within the chain).
void countTap(float lod) {
  if (countingThread) atomicAdd(groupTaps[clamp(int(floor(lod + 0.5)), 0, kHorizonDepthMipLevels - 1)], 1u);
}
#else
void countTap(float lod) {}
#endif

// XeGTAO_OutputWorkingTerm: visibility scaled into UNORM range by 1 / 1.5, 8 bits (with the bent
// normal as RGBA8).
void storeWorkingTerm(ivec2 pixel, float visibility, vec3 bentNormal) {
  visibility = clamp(visibility / kHorizonOcclusionTermScale, 0.0, 1.0);
  uint packedValue = kBent ? horizonPackUnorm8x4(vec4(bentNormal * 0.5 + 0.5, visibility)) : uint(visibility * 255.0 + 0.5);
  imageStore(workingAoTerm, pixel, uvec4(packedValue));
}

// XeGTAO_RotFromToMatrix(from, to) applied to v (Moller & Hughes; identity when nearly parallel).
vec3 rotateFromTo(vec3 from, vec3 to, vec3 v) {
  float e = dot(from, to);
  if (abs(e) > 1.0 - 0.0003) return v;
  vec3 c = cross(from, to);
  float h = 1.0 / (1.0 + e);
  float hvx = h * c.x, hvz = h * c.z;
  float hvxy = hvx * c.y, hvxz = hvx * c.z, hvyz = hvz * c.y;
  vec3 row0 = vec3(e + hvx * c.x, hvxy - c.z, hvxz + c.y);
  vec3 row1 = vec3(hvxy + c.z, e + h * c.y * c.y, hvyz - c.x);
  vec3 row2 = vec3(hvxz - c.y, hvyz + c.x, e + hvz * c.z);
  return vec3(dot(row0, v), dot(row1, v), dot(row2, v));
}

// The falloff terms of XeGTAO_MainPass: weight = saturate(distance * mul + add).
struct Falloff {
  float mul, add;
};

Falloff falloffOf(float effectRadius) {
  float falloffRange = pc.effectFalloffRange * effectRadius;
  float falloffFrom = effectRadius * (1.0 - pc.effectFalloffRange);
  return Falloff(-1.0 / falloffRange, falloffFrom / falloffRange + 1.0);
}

// A sample's falloff weight (delta: sample minus centre, dist its length), thin occluders
// compensated when the key is set.
float falloffWeight(vec3 delta, float dist, Falloff falloff) {
  float falloffBase = kThin ? length(vec3(delta.xy, delta.z * (1.0 + pc.thinOccluderCompensation))) : dist;
  return clamp(falloffBase * falloff.mul + falloff.add, 0.0, 1.0);
}

// The view-space position of the depth tap at `samplePos` (counted for --debug mip_taps).
vec3 tapPosition(vec2 samplePos, float mipLevel) {
  float sampleZ = textureLod(depthMips, samplePos, mipLevel).x;
  countTap(mipLevel);
  return horizonViewPosition(samplePos, sampleZ);
}

// Algorithm 1 of the GTAO paper as XeGTAO_MainPass runs it: per slice the projected normal's angle,
// the horizon search on both sides, the analytic integral (and the bent normal of Algorithm 2).
float horizonSearch(vec2 screenPos, vec3 centre, vec3 viewVec, vec3 normal, float viewZ, vec2 noise, out vec3 bentNormal) {
  float effectRadius = pc.effectRadius * pc.radiusMultiplier;
  Falloff falloff = falloffOf(effectRadius);
  float sliceCount = float(kSlices), stepsPerSlice = float(kSteps);
  float visibility = 0.0;
  bentNormal = kBent ? vec3(0.0) : normal;
  vec2 pixelDirRBViewspaceSizeAtCenterZ = vec2(viewZ) * pc.ndcToViewMulXPixelSize;
  float screenspaceRadius = effectRadius / pixelDirRBViewspaceSizeAtCenterZ.x;
  visibility += clamp((10.0 - screenspaceRadius) / 100.0, 0.0, 1.0) * 0.5;  // fade out for small screen radii
  float minS = kHorizonPixelTooClose / screenspaceRadius;  // never sample the centre pixel

  for (float slice = 0.0; slice < sliceCount; slice += 1.0) {
    float phi = ((slice + noise.x) / sliceCount) * kHorizonPi;
    float cosPhi = cos(phi), sinPhi = sin(phi);
    vec2 omega = vec2(cosPhi, -sinPhi) * screenspaceRadius;  // pixels, y down
    vec3 directionVec = vec3(cosPhi, sinPhi, 0.0);
    vec3 orthoDirectionVec = directionVec - dot(directionVec, viewVec) * viewVec;
    vec3 axisVec = normalize(cross(orthoDirectionVec, viewVec));
    vec3 projectedNormalVec = normal - axisVec * dot(normal, axisVec);
    float signNorm = sign(dot(orthoDirectionVec, projectedNormalVec));
    float projectedNormalVecLength = length(projectedNormalVec);
    float cosNorm = clamp(dot(projectedNormalVec, viewVec) / projectedNormalVecLength, 0.0, 1.0);
    float n = signNorm * horizonFastAcos(cosNorm);
    float lowHorizonCos0 = cos(n + kHorizonHalfPi);
    float lowHorizonCos1 = cos(n - kHorizonHalfPi);
    float horizonCos0 = lowHorizonCos0, horizonCos1 = lowHorizonCos1;

    [[unroll]] for (float stepIndex = 0.0; stepIndex < stepsPerSlice; stepIndex += 1.0) {
      float stepBaseNoise = float(slice + stepIndex * stepsPerSlice) * 0.6180339887498948482;  // R1
      float stepNoise = fract(noise.y + stepBaseNoise);
      float s = (stepIndex + stepNoise) / stepsPerSlice;
      s = pow(s, kSampleDistributionPower);
      s += minS;
      // Statement for statement in XeGTAO_MainPass's sequence: tap 0, tap 1, then each step of the
      // horizon for both side by side. The same operations in the port's earlier order (one
      // function a tap) made the main pass 1.6-2 % slower than XeGTAO's on an H200 (same
      // registers, same results), and one tap's horizon between the two taps 5 % on lavapipe.
      vec2 sampleOffset = s * omega;
      float mipLevel = clamp(log2(length(sampleOffset)) - pc.depthMipSamplingOffset, 0.0, float(kHorizonDepthMipLevels));
      sampleOffset = roundEven(sampleOffset) * pc.viewportPixelSize;  // snapped to pixel centres (HLSL round: halves to even)
      vec3 samplePos0 = tapPosition(screenPos + sampleOffset, mipLevel);
      vec3 samplePos1 = tapPosition(screenPos - sampleOffset, mipLevel);
      vec3 sampleDelta0 = samplePos0 - centre;
      vec3 sampleDelta1 = samplePos1 - centre;
      float sampleDist0 = length(sampleDelta0);
      float sampleDist1 = length(sampleDelta1);
      vec3 sampleHorizonVec0 = sampleDelta0 / sampleDist0;
      vec3 sampleHorizonVec1 = sampleDelta1 / sampleDist1;
      float weight0 = falloffWeight(sampleDelta0, sampleDist0, falloff);
      float weight1 = falloffWeight(sampleDelta1, sampleDist1, falloff);
      float shc0 = dot(sampleHorizonVec0, viewVec);
      float shc1 = dot(sampleHorizonVec1, viewVec);
      shc0 = mix(lowHorizonCos0, shc0, weight0);
      shc1 = mix(lowHorizonCos1, shc1, weight1);
      horizonCos0 = max(horizonCos0, shc0);
      horizonCos1 = max(horizonCos1, shc1);
    }

    projectedNormalVecLength = mix(projectedNormalVecLength, 1.0, 0.05);  // XeGTAO's slope fudge
    float h0 = -horizonFastAcos(horizonCos1);
    float h1 = horizonFastAcos(horizonCos0);
    float iarc0 = (cosNorm + 2.0 * h0 * sin(n) - cos(2.0 * h0 - n)) / 4.0;
    float iarc1 = (cosNorm + 2.0 * h1 * sin(n) - cos(2.0 * h1 - n)) / 4.0;
    visibility += projectedNormalVecLength * (iarc0 + iarc1);

    if (kBent) {
      float t0 = (6.0 * sin(h0 - n) - sin(3.0 * h0 - n) + 6.0 * sin(h1 - n) - sin(3.0 * h1 - n) + 16.0 * sin(n) -
                  3.0 * (sin(h0 + n) + sin(h1 + n))) / 12.0;
      float t1 = (-cos(3.0 * h0 - n) - cos(3.0 * h1 - n) + 8.0 * cos(n) - 3.0 * (cos(h0 + n) + cos(h1 + n))) / 12.0;
      vec3 localBentNormal = vec3(directionVec.x * t0, directionVec.y * t0, -t1);
      bentNormal += rotateFromTo(vec3(0.0, 0.0, -1.0), viewVec, localBentNormal) * projectedNormalVecLength;
    }
  }
  visibility /= sliceCount;
  visibility = pow(visibility, pc.finalValuePower);
  visibility = max(kHorizonVisibilityFloor, visibility);
  if (kBent) bentNormal = normalize(bentNormal);
  return visibility;
}

void main() {
#ifdef XEGTAO_COUNT_TAPS
  if (gl_LocalInvocationIndex < uint(kHorizonDepthMipLevels)) groupTaps[gl_LocalInvocationIndex] = 0u;
  barrier();
#endif
  // Straight-line code as XeGTAO's (no branch around the work): a thread past the edge computes
  // its clamped pixel and stores nothing; a sky pixel computes and stores XeGTAO's value.
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  bool inside = all(lessThan(pixel, pc.viewportSize));  // no short-circuit branch
  pixel = min(pixel, pc.viewportSize - 1);
#ifdef XEGTAO_COUNT_TAPS
  countingThread = inside;
#endif
  // vaGTAO's CSGTAOHigh order: the noise and the normal, then XeGTAO_MainPass's body (the order
  // is part of the main pass's speed on an H200: see the step loop).
  vec2 noise = horizonNoise(uvec2(pixel), uint(pc.noiseIndex));
  vec3 normal = normalize(horizonFromToolView(imageLoad(viewNormals, pixel).xyz));  // LoadNormal normalises
  vec2 screenPos = (vec2(pixel) + 0.5) * pc.viewportPixelSize;
  vec2 cornerPos = vec2(pixel) * pc.viewportPixelSize;
  vec4 valuesUL = textureGather(depthMips, cornerPos);                    // x L, y centre, z T
  vec4 valuesBR = textureGatherOffset(depthMips, cornerPos, ivec2(1, 1));  // x B, z R
  float viewZ = valuesUL.y;
  vec4 edges = horizonEdges(viewZ, valuesUL.x, valuesBR.z, valuesUL.z, valuesBR.x);
  if (inside) imageStore(workingEdges, pixel, vec4(horizonPackEdges(edges)));

  viewZ *= kDepth32 ? kHorizonDepth32PullIn : kHorizonDepth16PullIn;  // against depth imprecision
  vec3 centre = horizonViewPosition(screenPos, viewZ);
  vec3 viewVec = normalize(-centre);
  vec3 bentNormal;
  float visibility = horizonSearch(screenPos, centre, viewVec, normal, viewZ, noise, bentNormal);
  // Sky keeps XeGTAO's value here, as XeGTAO's denoiser sees it; the last denoise pass sets it to 1.
  if (inside) storeWorkingTerm(pixel, visibility, bentNormal);
#ifdef XEGTAO_COUNT_TAPS
  barrier();
  if (gl_LocalInvocationIndex < uint(kHorizonDepthMipLevels))
    atomicAdd(mipTaps[gl_LocalInvocationIndex], groupTaps[gl_LocalInvocationIndex]);
#endif
}
