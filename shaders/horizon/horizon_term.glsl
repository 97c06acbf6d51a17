// XeGTAO's working term and the last pass's output, as the denoiser and the sky pass store them.
// The includer declares `HorizonConstants pc` and `kBent` and includes xegtao_common.glsl first.

// AOTermType: visibility in w (bent normal, XeGTAO's view space, in xyz when kBent).
vec4 decodeTerm(uint packedValue) {
  if (!kBent) return vec4(float(packedValue) / 255.0);
  vec4 decoded = horizonUnpackUnorm8x4(packedValue);
  return vec4(decoded.xyz * 2.0 - 1.0, decoded.w);
}

// XeGTAO_Output's packing of a term (`scale`: 1.5 in the last pass, which undoes the main pass's
// XE_GTAO_OCCLUSION_TERM_SCALE, 1 before it).
uint horizonPackTerm(vec4 term, float scale) {
  if (kBent) return horizonPackUnorm8x4(vec4(normalize(term.xyz) * 0.5 + 0.5, term.w * scale));
  return uint(term.w * scale * 255.0 + 0.5);
}

// What the engine reads from XeGTAO's 8-bit output for a term of the last pass, as the float value
// this tool's output image holds: above 255 (visibility over 1 after the scale) it is full
// visibility; bent normals back in this tool's view space.
vec4 horizonEngineValue(vec4 term) {
  uint packedValue = horizonPackTerm(term, kHorizonOcclusionTermScale);
  if (!kBent) return vec4(float(min(packedValue, 255u)) / 255.0);
  vec4 decoded = decodeTerm(packedValue);
  return vec4(horizonFromToolView(decoded.xyz), decoded.w);
}
