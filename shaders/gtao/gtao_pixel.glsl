// GTAO horizon search and integration for one pixel (seed 000 pass 1), shared by gtao.comp and the
// CPU mirror. The includer provides:
//   GtaoConstants pc; int kSlices, kSteps; bool kBent; bool kThin (pc.thin > 0);
//   float gtaoLoadDistance(ivec2 pixel)      linear view distance, <= 0 for sky/invalid; pixel in range
//   vec3  gtaoLoadViewNormal(ivec2 pixel)    view-space normal as stored: any length, zero, NaN or Inf
// Returns visibility in [0,1] and the bent normal (view space, unit) through `bentNormal`.

// What every sample of a pixel shares: its view-space position, view vector and normal, and the
// sampling constants derived from the push constants once per pixel rather than once per sample.
struct GtaoCentre {
  vec3 position;
  vec2 viewRay;         // view-space xy of the pixel's centre at distance 1
  vec3 viewDir;
  vec3 normal;
  float screenRadius;   // pixels
  float invFadeWidth;   // 1 / gtaoFadeWidth
  float thinStretch;    // (1 + thin)^2 - 1: the thin heuristic's extra weight on the depth component
};

// Horizon cosine (angle from the view vector, within the slice) of one sample, blended toward the
// tangent-plane horizon `lowCos` as the sample's falloff weight drops. Off-screen and sky samples
// occlude nothing.
// Deviation from seed 000 / XeGTAO, on purpose: the sample's elevation is measured above the
// tangent plane (sin e = dot(delta, N) / (|delta| |projected N|), exact for samples inside the
// slice) and turned into a slice angle (trace of the tangent plane at n +- pi/2, minus e). Samples
// snapped to pixel centres leave the slice plane; measuring their cosine to the view vector
// directly makes flat planes occlude themselves (0.92 at 30 degrees), this makes planes exact.
// Branch-free on purpose: a CPU device (lavapipe) runs both sides of every branch anyway, and the
// final select drops whatever an unusable sample computed (NaN included).
float gtaoSampleHorizonCos(ivec2 samplePixel, vec2 rayOffset, GtaoCentre c, float invProjectedLength, float cosN,
                           float sinN, float side) {
  float lowCos = gtaoTangentHorizonCos(sinN, side);
  ivec2 fetched = clamp(samplePixel, ivec2(0), pc.size - 1);
  float dist = gtaoLoadDistance(fetched);
  // The sample's view position from the centre's ray, one pixel step per pixel of offset (the
  // projection is affine in the pixel coordinate; rayOffset is the offset times viewPerPixel,
  // signed by side); an off-screen sample is not used.
  vec2 ray = c.viewRay + rayOffset;
  vec3 delta = vec3(dist * ray, -dist) - c.position;
  float len2 = dot(delta, delta);
  float invLen = inversesqrt(len2);
  // Thin-occluder heuristic (XeGTAO): stretching the depth component fades samples behind the
  // centre sooner, so thin objects do not cast a full horizon. Without it the falloff distance is
  // the length itself, and one inverse square root serves both (a square root less per sample).
  float falloffDist = kThin ? sqrt(len2 + delta.z * delta.z * c.thinStretch) : len2 * invLen;
  float weight = gtaoFalloffWeight(falloffDist, pc.radius, c.invFadeWidth);
  float sinE = clamp(dot(delta, c.normal) * invLen * invProjectedLength, -1.0f, 1.0f);
  float cosE = sqrt(1.0f - sinE * sinE);
  // side +1: cos(n + pi/2 - e); side -1: cos(n - pi/2 + e)
  float sampleCos = cosN * sinE - side * sinN * cosE;
  // falloffDist < radius is weight > 0, false for NaN (len2 = 0 or Inf makes len2 * invLen NaN),
  // and bounds len2 by radius^2: no overflowing distance gets through.
  bool usable = fetched == samplePixel && dist > 0.0f && falloffDist < pc.radius && len2 > 0.0f;
  return usable ? mix(lowCos, sampleCos, weight) : lowCos;
}

// What every slice needs: its view-space direction and the projected normal's angle n (with cos
// and sin) in the slice plane.
struct GtaoSlice {
  vec3 direction;
  float projectedLength, invProjectedLength;
  float n, cosN, sinN;
};

// False when the normal lies along the slice axis: such a slice sees nothing.
bool gtaoSliceFrame(vec2 omega, vec3 viewDir, vec3 normal, AOR_OUT(GtaoSlice) slice) {
  slice.direction = normalize(vec3(omega.x * pc.viewPerPixel.x, omega.y * pc.viewPerPixel.y, 0.0f));
  // direction has z = 0 and viewDir.z > 0, so they are never parallel. The axis is the cross
  // product of two orthogonal unit vectors: unit without normalising. (1 - along^2 instead of the
  // orthogonal part's length cancels at very wide fields of view: 8e-3 error at 4100x2.)
  vec3 orthoDirection = normalize(slice.direction - dot(slice.direction, viewDir) * viewDir);
  vec3 axis = cross(orthoDirection, viewDir);
  vec3 projectedNormal = normal - axis * dot(normal, axis);
  float projectedLength2 = dot(projectedNormal, projectedNormal);
  if (!(projectedLength2 > 1e-12f)) return false;
  slice.invProjectedLength = inversesqrt(projectedLength2);
  slice.projectedLength = projectedLength2 * slice.invProjectedLength;

  // n from the projected normal's two components in the slice plane: acos(cosN) and
  // sqrt(1 - cosN^2) lose half the digits for surfaces facing the viewer (cosN near 1; 3e-4 rad
  // in float32), atan does not. A normal facing away is limited to the horizon (n = +-pi/2).
  float normalAlong = dot(projectedNormal, viewDir);
  float normalAcross = dot(projectedNormal, orthoDirection);
  float signN = normalAcross >= 0.0f ? 1.0f : -1.0f;
  bool facesViewer = normalAlong > 0.0f;
  slice.cosN = facesViewer ? clamp(normalAlong * slice.invProjectedLength, 0.0f, 1.0f) : 0.0f;
  slice.n = facesViewer ? signN * atan(abs(normalAcross), normalAlong) : signN * kHalfPi;
  slice.sinN = facesViewer ? clamp(normalAcross * slice.invProjectedLength, -1.0f, 1.0f) : signN;
  return true;
}

// The samples at +offset and -offset pixels, raising each side's horizon.
void gtaoSampleBothSides(ivec2 pixel, ivec2 offset, GtaoCentre c, GtaoSlice slice, AOR_INOUT(float) horizonCosPos,
                         AOR_INOUT(float) horizonCosNeg) {
  // Converted once for both sides: int-to-float conversion is a quarter-rate instruction on NVIDIA
  // GPUs (H100 gtao -2 %, bench/RESULTS.md).
  vec2 rayOffset = vec2(offset) * pc.viewPerPixel;
  horizonCosPos = max(horizonCosPos, gtaoSampleHorizonCos(pixel + offset, rayOffset, c, slice.invProjectedLength,
                                                          slice.cosN, slice.sinN, 1.0f));
  horizonCosNeg = max(horizonCosNeg, gtaoSampleHorizonCos(pixel - offset, -rayOffset, c, slice.invProjectedLength,
                                                          slice.cosN, slice.sinN, -1.0f));
}

// Integrates one slice whose horizon cosines were found, into the pixel's running sums. The bent
// normal is summed in the frame where the view vector is +Z: the rotation to view space is linear,
// so gtaoResolve applies it once per pixel instead of once per slice.
void gtaoAccumulateSlice(GtaoSlice slice, float horizonCosPos, float horizonCosNeg,
                         AOR_INOUT(float) visibility, AOR_INOUT(float) unoccluded, AOR_INOUT(vec3) bentSum) {
  float n = slice.n, cosN = slice.cosN, sinN = slice.sinN;
  // Horizons as angles from the view vector, limited to the hemisphere around the normal: with
  // n in [-pi/2, pi/2] that is hPos <= n + pi/2 and hNeg >= n - pi/2 (the other bounds hold for
  // any acos), i.e. the cosines bounded by the tangent-plane horizons. Clamping the cosines keeps
  // cos/sin of each horizon exact, so no cos/sin of an angle is needed (seed 000 asks for none
  // beyond the AO integral's; this needs only the two acos).
  float cosPos = clamp(horizonCosPos, -sinN, 1.0f);
  float cosNeg = clamp(horizonCosNeg, sinN, 1.0f);
  float sinPos = sqrt(1.0f - cosPos * cosPos);
  float sinNeg = -sqrt(1.0f - cosNeg * cosNeg);
  float hPos = acos(cosPos);
  float hNeg = -acos(cosNeg);
  visibility += slice.projectedLength * (gtaoHorizonVisibility(hPos, cosPos, sinPos, cosN, sinN) +
                                         gtaoHorizonVisibility(hNeg, cosNeg, sinNeg, cosN, sinN));
  unoccluded += slice.projectedLength * gtaoUnoccludedSlice(n, cosN, sinN);
  if (kBent) {
    vec2 terms = gtaoHorizonBentTerms(cosNeg, sinNeg, cosN, sinN) + gtaoHorizonBentTerms(cosPos, sinPos, cosN, sinN);
    vec2 b = vec2((terms.x + 16.0f * sinN) / 12.0f, (terms.y + 8.0f * cosN) / 12.0f);
    vec3 sliceBent = vec3(slice.direction.x * b.x, slice.direction.y * b.x, b.y);
    bentSum += sliceBent * slice.projectedLength;
  }
}

// The centre of a pixel's search; false for sky (visibility 1, bent normal toward the viewer).
bool gtaoPixelCentre(ivec2 pixel, AOR_OUT(GtaoCentre) c) {
  float dist = gtaoLoadDistance(pixel);
  if (dist <= 0.0f) return false;
  c.viewRay = pixelToNdc(vec2(pixel), pc.invSize) * pc.ndcToViewMul + pc.ndcToViewAdd;
  c.position = vec3(dist * c.viewRay, -dist);
  c.viewDir = normalize(-c.position);
  vec3 normal = gtaoLoadViewNormal(pixel);
  float len2 = dot(normal, normal);
  // A zero, NaN or Inf normal is unusable: assume the surface faces the viewer.
  c.normal = (len2 > 1e-12f && !isinf(len2)) ? normal * inversesqrt(len2) : c.viewDir;
  c.screenRadius = min(pc.radius * pc.pixelsPerUnit / dist, length(vec2(pc.size)));
  c.invFadeWidth = 1.0f / gtaoFadeWidth(pc.radius, pc.falloffRange);
  c.thinStretch = (1.0f + pc.thin) * (1.0f + pc.thin) - 1.0f;
  return true;
}

// Deviation from seed 000 / XeGTAO, on purpose: divide by the unoccluded integral of the same
// slices instead of the slice count. Both tend to the same value as slices grow, but a single
// unoccluded slice integrates to projLen * (cos n + n sin n), not 1, so dividing by the count
// makes tilted planes scatter around 1 (0.92 at 30 degrees with 9 slices); the ratio is exact.
float gtaoResolve(float visibility, float unoccluded, vec3 bentSum, vec3 viewDir, vec3 normal, AOR_OUT(vec3) bentNormal) {
  visibility = unoccluded > 0.0f ? clamp(visibility / unoccluded, 0.0f, 1.0f) : 1.0f;
  if (pc.power != 1.0f) visibility = pow(visibility, pc.power);  // pow(x, 1) is exp2(log2(x)) on some devices
  if (kBent) {
    vec3 bentView = rotateZTo(viewDir, bentSum);
    float bentLength = length(bentView);
    bentNormal = bentLength > 1e-6f ? bentView / bentLength : normal;
  }
  return visibility;
}

// One slice along screen direction omega: its frame, horizon search on both sides and integral,
// added to the pixel's running sums.
void gtaoSlice(ivec2 pixel, GtaoCentre c, vec2 omega, float stepNoise, AOR_INOUT(float) visibility,
               AOR_INOUT(float) unoccluded, AOR_INOUT(vec3) bentSum) {
  GtaoSlice slice;
  if (!gtaoSliceFrame(omega, c.viewDir, c.normal, slice)) return;
  float horizonCosPos = gtaoTangentHorizonCos(slice.sinN, 1.0f);
  float horizonCosNeg = gtaoTangentHorizonCos(slice.sinN, -1.0f);
  AOR_UNROLL for (int step = 0; step < kSteps; ++step) {
    float t = (float(step) + stepNoise) / float(kSteps);
    float offsetPixels = t * t * c.screenRadius + kMinSampleOffsetPixels;  // quadratic distribution
    gtaoSampleBothSides(pixel, ivec2(round(omega * offsetPixels)), c, slice, horizonCosPos, horizonCosNeg);
  }
  gtaoAccumulateSlice(slice, horizonCosPos, horizonCosNeg, visibility, unoccluded, bentSum);
}

vec2 gtaoRotate(vec2 v, vec2 cosSin) {
  return vec2(v.x * cosSin.x - v.y * cosSin.y, v.x * cosSin.y + v.y * cosSin.x);
}

// `noise` is gtaoNoise of the pixel's place in the image GTAO writes: the pixel itself at full
// resolution, its half-resolution texel otherwise (see gtao.comp).
float gtaoPixelWithNoise(ivec2 pixel, vec2 noise, AOR_OUT(vec3) bentNormal) {
  bentNormal = vec3(0.0f, 0.0f, 1.0f);
  GtaoCentre c;
  if (!gtaoPixelCentre(pixel, c)) return 1.0f;

  float visibility = 0.0f;
  float unoccluded = 0.0f;  // what the same slices integrate to with no occluder at all
  vec3 bentSum = vec3(0.0f);
  // Slice directions are evenly spaced: one cos/sin per pixel, then a rotation per slice.
  float phi = noise.x * (kPi / float(kSlices));
  vec2 omega = vec2(cos(phi), sin(phi));  // screen direction, pixels, y down
  vec2 sliceRotation = vec2(cos(kPi / float(kSlices)), sin(kPi / float(kSlices)));
  // The same loop twice, so that only small ones are unrolled: unrolled, lavapipe runs 3x3 in
  // 9.1 ms instead of 12.5 at 640x360, but it compiles a shader on its first dispatch, and that
  // grows with the unrolled size (first dispatch at 320x180 with no shader cache: 0.39 s at 9x3
  // against 0.08 rolled, 2.3 s at 16x8, 13-21 s at 32x12 to 32x16; bench/RESULTS.md). The
  // condition is a specialisation constant, so the other loop is never compiled.
  if (kSlices * kSteps <= kGtaoMaxUnrolledSliceSteps) {
    AOR_UNROLL for (int sliceIndex = 0; sliceIndex < kSlices; ++sliceIndex) {
      gtaoSlice(pixel, c, omega, noise.y, visibility, unoccluded, bentSum);
      omega = gtaoRotate(omega, sliceRotation);
    }
  } else {
    for (int sliceIndex = 0; sliceIndex < kSlices; ++sliceIndex) {
      gtaoSlice(pixel, c, omega, noise.y, visibility, unoccluded, bentSum);
      omega = gtaoRotate(omega, sliceRotation);
    }
  }
  return gtaoResolve(visibility, unoccluded, bentSum, c.viewDir, c.normal, bentNormal);
}

float gtaoPixel(ivec2 pixel, AOR_OUT(vec3) bentNormal) {
  return gtaoPixelWithNoise(pixel, gtaoNoise(pixel, pc.frameIndex), bentNormal);
}
