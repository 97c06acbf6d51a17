// vbao's main pass: per pixel, slices x steps samples as xegtao's main pass takes them (the same
// noise, step positions, MIP levels and centre), each sample a slab of `thickness` behind the
// depth it reads, marking the sectors of the slice's hemisphere between its front and back
// angles; visibility is what the unmarked sectors weigh (uniform: their share; cosine: GTAO's arc
// integral over them). Writes the horizon blocks' working term and edges for the shared denoiser.
// Built as main_pass.comp, and main_pass_sectors.comp (VBAO_SECTORS_VIEW) which also writes the
// share of sectors occupied (--debug sectors).
#include "vbao.h"

layout(local_size_x = kHorizonWorkgroupSize, local_size_y = kHorizonWorkgroupSize) in;
layout(constant_id = kVbaoSpecSlices) const int kSlices = 3;
layout(constant_id = kVbaoSpecSteps) const int kSteps = 3;
layout(constant_id = kVbaoSpecSectors) const uint kSectors = 32u;
layout(constant_id = kVbaoSpecCosine) const bool kCosine = true;
layout(constant_id = kHorizonSpecDepth32) const bool kDepth32 = false;
layout(constant_id = kVbaoSpecSampleDistributionPower) const float kSampleDistributionPower = 2.0;
const bool kBent = false;  // horizon_term.glsl's encodings: visibility only

layout(push_constant, scalar) uniform Push { VbaoConstants vc; };
#define pc vc.horizon
layout(set = 0, binding = 0) uniform sampler2D depthMips;   // the shared chain, nearest (texels and levels), clamped
layout(set = 0, binding = 1, rgba16f) uniform readonly image2D viewNormals;  // the front's, this tool's view space
layout(set = 0, binding = 2) uniform writeonly uimage2D workingAoTerm;       // R8_UINT
layout(set = 0, binding = 3) uniform writeonly image2D workingEdges;         // R8_UNORM
#ifdef VBAO_SECTORS_VIEW
layout(set = 0, binding = 4) uniform writeonly image2D sectorsView;          // R32F
#endif

#include "horizon/horizon_common.glsl"

// A sample's falloff weight over the outer falloff_range of the radius (XeGTAO's), 1 inside.
float falloffWeight(float dist, float effectRadius) {
  float falloffRange = pc.effectFalloffRange * effectRadius;
  float falloffFrom = effectRadius * (1.0 - pc.effectFalloffRange);
  return clamp((falloffFrom - dist) / falloffRange + 1.0, 0.0, 1.0);
}

// The slice's geometry: the projected normal's angle n (XeGTAO's), its cos and sin, the projected
// normal's length (with XeGTAO's slope fudge) and the two sides' low horizons.
struct Slice {
  vec2 omega;  // pixels to the radius along the slice, y down
  float n, cosN, sinN, normalLength;
  float lowCos0, lowCos1;
};

Slice sliceOf(float phi, float screenspaceRadius, vec3 viewVec, vec3 normal) {
  Slice s;
  float cosPhi = cos(phi), sinPhi = sin(phi);
  s.omega = vec2(cosPhi, -sinPhi) * screenspaceRadius;
  vec3 directionVec = vec3(cosPhi, sinPhi, 0.0);
  vec3 orthoDirectionVec = directionVec - dot(directionVec, viewVec) * viewVec;
  vec3 axisVec = normalize(cross(orthoDirectionVec, viewVec));
  vec3 projectedNormalVec = normal - axisVec * dot(normal, axisVec);
  float signNorm = sign(dot(orthoDirectionVec, projectedNormalVec));
  float projectedLength = length(projectedNormalVec);
  s.cosN = clamp(dot(projectedNormalVec, viewVec) / projectedLength, 0.0, 1.0);
  s.n = signNorm * horizonFastAcos(s.cosN);
  s.sinN = sin(s.n);
  s.normalLength = mix(projectedLength, 1.0, 0.05);
  s.lowCos0 = cos(s.n + kHorizonHalfPi);
  s.lowCos1 = cos(s.n - kHorizonHalfPi);
  return s;
}

// The sectors one sample's slab occupies: front angle from the sample, back angle from the sample
// moved `thickness` away along the view direction; both fall back to the side's low horizon as
// the sample's falloff weight goes to 0. side 0: positive angles, side 1: negative.
uint sampleSectors(vec3 delta, vec3 viewVec, float effectRadius, Slice s, float lowCos, float side) {
  float dist = length(delta);
  float weight = falloffWeight(dist, effectRadius);
  vec3 back = delta - viewVec * vc.thickness;
  float frontCos = mix(lowCos, dot(delta / dist, viewVec), weight);
  float backCos = mix(lowCos, dot(normalize(back), viewVec), weight);
  float frontAngle = horizonFastAcos(frontCos), backAngle = horizonFastAcos(backCos);
  float lo = side == 0.0 ? frontAngle : -backAngle;
  float hi = side == 0.0 ? backAngle : -frontAngle;
  return vbaoSectorMask(vbaoHemisphereFraction(lo, s.n), vbaoHemisphereFraction(hi, s.n), kSectors);
}

// What the unoccupied sectors weigh: their share (uniform), or GTAO's arc integral over each run
// of them (cosine), the projected normal's length as XeGTAO weighs a slice.
float sliceVisibility(uint occupied, Slice s) {
  uint all = kSectors >= 32u ? 0xffffffffu : ((1u << kSectors) - 1u);
  uint open = ~occupied & all;
  if (!kCosine) return float(bitCount(open)) / float(kSectors);
  float sum = 0.0;
  float sectorAngle = kHorizonPi / float(kSectors), start = s.n - kHorizonHalfPi;
  while (open != 0u) {
    int first = findLSB(open);
    uint rest = open >> uint(first);
    int end = first + (rest == 0xffffffffu ? 32 : findLSB(~rest));  // the run's end (at most kSectors)
    sum += vbaoCosineCumulative(start + float(end) * sectorAngle, s.n, s.cosN, s.sinN) -
           vbaoCosineCumulative(start + float(first) * sectorAngle, s.n, s.cosN, s.sinN);
    uint run = end - first >= 32 ? 0xffffffffu : ((1u << uint(end - first)) - 1u);
    open &= ~(run << uint(first));
  }
  return sum * s.normalLength;
}

// The slices: xegtao's sample positions, each sample's slab into the slice's bits.
float bitmaskSearch(vec2 screenPos, vec3 centre, vec3 viewVec, vec3 normal, float viewZ, vec2 noise, out float occupiedShare) {
  float effectRadius = pc.effectRadius * pc.radiusMultiplier;
  float sliceCount = float(kSlices), stepsPerSlice = float(kSteps);
  float screenspaceRadius = effectRadius / (viewZ * pc.ndcToViewMulXPixelSize.x);
  float visibility = clamp((10.0 - screenspaceRadius) / 100.0, 0.0, 1.0) * 0.5;  // XeGTAO's fade for small radii
  float minS = kHorizonPixelTooClose / screenspaceRadius;
  occupiedShare = 0.0;
  for (float slice = 0.0; slice < sliceCount; slice += 1.0) {
    Slice s = sliceOf(((slice + noise.x) / sliceCount) * kHorizonPi, screenspaceRadius, viewVec, normal);
    uint occupied = 0u;
    [[unroll]] for (float stepIndex = 0.0; stepIndex < stepsPerSlice; stepIndex += 1.0) {
      float stepNoise = fract(noise.y + float(slice + stepIndex * stepsPerSlice) * 0.6180339887498948482);
      float t = pow((stepIndex + stepNoise) / stepsPerSlice, kSampleDistributionPower) + minS;
      vec2 sampleOffset = t * s.omega;
      float mipLevel = clamp(log2(length(sampleOffset)) - pc.depthMipSamplingOffset, 0.0, float(kHorizonDepthMipLevels));
      sampleOffset = roundEven(sampleOffset) * pc.viewportPixelSize;
      vec3 delta0 = horizonViewPosition(screenPos + sampleOffset, textureLod(depthMips, screenPos + sampleOffset, mipLevel).x) - centre;
      vec3 delta1 = horizonViewPosition(screenPos - sampleOffset, textureLod(depthMips, screenPos - sampleOffset, mipLevel).x) - centre;
      occupied |= sampleSectors(delta0, viewVec, effectRadius, s, s.lowCos0, 0.0);
      occupied |= sampleSectors(delta1, viewVec, effectRadius, s, s.lowCos1, 1.0);
    }
    visibility += sliceVisibility(occupied, s);
    occupiedShare += float(bitCount(occupied)) / float(kSectors);
  }
  occupiedShare /= sliceCount;
  visibility /= sliceCount;
  return max(kHorizonVisibilityFloor, pow(visibility, pc.finalValuePower));
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  bool inside = all(lessThan(pixel, pc.viewportSize));
  pixel = min(pixel, pc.viewportSize - 1);
  vec2 noise = horizonNoise(uvec2(pixel), uint(pc.noiseIndex));
  vec3 normal = normalize(horizonFromToolView(imageLoad(viewNormals, pixel).xyz));
  vec2 screenPos = (vec2(pixel) + 0.5) * pc.viewportPixelSize;
  vec2 cornerPos = vec2(pixel) * pc.viewportPixelSize;
  vec4 valuesUL = textureGather(depthMips, cornerPos);                    // x L, y centre, z T
  vec4 valuesBR = textureGatherOffset(depthMips, cornerPos, ivec2(1, 1));  // x B, z R
  float viewZ = valuesUL.y;
  vec4 edges = horizonEdges(viewZ, valuesUL.x, valuesBR.z, valuesUL.z, valuesBR.x);
  if (inside) imageStore(workingEdges, pixel, vec4(horizonPackEdges(edges)));

  viewZ *= kDepth32 ? kHorizonDepth32PullIn : kHorizonDepth16PullIn;
  vec3 centre = horizonViewPosition(screenPos, viewZ);
  vec3 viewVec = normalize(-centre);
  float occupiedShare;
  float visibility = bitmaskSearch(screenPos, centre, viewVec, normal, viewZ, noise, occupiedShare);
  // The working term as the shared denoiser reads it: visibility / 1.5 in 8 bits.
  if (inside) imageStore(workingAoTerm, pixel, uvec4(uint(clamp(visibility / kHorizonOcclusionTermScale, 0.0, 1.0) * 255.0 + 0.5)));
#ifdef VBAO_SECTORS_VIEW
  if (inside) imageStore(sectorsView, pixel, vec4(occupiedShare));
#endif
}
