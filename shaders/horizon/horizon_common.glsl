// What XeGTAO's three passes share on the GPU side: view-space positions, depth unpacking, edges
// and their packing, the visibility (and bent-normal) encodings, the fast sqrt/acos. Each function
// names the XeGTAO.hlsli function it ports (replay/techniques/xegtao/README.md: the full table).
// The includer declares `HorizonConstants pc`.

const float kHorizonPi = 3.1415926535897932384626433832795;
const float kHorizonHalfPi = 1.5707963267948966192313216916398;

// XeGTAO_ComputeViewspacePosition: screen uv and view z to XeGTAO's view space.
vec3 horizonViewPosition(vec2 screenPos, float viewZ) {
  return vec3((pc.ndcToViewMul * screenPos + pc.ndcToViewAdd) * viewZ, viewZ);
}

// XeGTAO_ScreenSpaceToViewSpaceDepth, four at once.
vec4 horizonUnclampedViewDepth(vec4 screenDepth) {
  return pc.depthUnpackConsts.x / (pc.depthUnpackConsts.y - screenDepth);
}

// XeGTAO_ClampDepth. NaN depth (invalid input) is taken as the farthest depth rather than left to
// clamp's undefined NaN handling (a select between two values: glslang would branch on a ternary
// of expressions).
vec4 horizonClampDepth(vec4 z) {
  vec4 clamped = clamp(z, 0.0, kHorizonMaxDepth);
  return mix(clamped, vec4(kHorizonMaxDepth), isnan(z));
}

// XeGTAO_CalculateEdges: per side, 1 where the neighbour continues the surface (its depth within
// 1.1 % of z of the slope-adjusted prediction), falling to 0 beyond.
vec4 horizonEdges(float centerZ, float leftZ, float rightZ, float topZ, float bottomZ) {
  vec4 delta = vec4(leftZ, rightZ, topZ, bottomZ) - centerZ;
  float slopeLR = (delta.y - delta.x) * 0.5;
  float slopeTB = (delta.w - delta.z) * 0.5;
  vec4 slopeAdjusted = delta + vec4(slopeLR, -slopeLR, slopeTB, -slopeTB);
  delta = min(abs(delta), abs(slopeAdjusted));
  return clamp(1.25 - delta / (centerZ * kHorizonEdgeSensitivity), 0.0, 1.0);
}

// XeGTAO_PackEdges: 2 bits a side (left in the top bits), as the unorm value the R8_UNORM image holds.
float horizonPackEdges(vec4 edgesLRTB) {
  edgesLRTB = roundEven(clamp(edgesLRTB, 0.0, 1.0) * 2.9);  // HLSL round: halves to even
  return dot(edgesLRTB, vec4(64.0 / 255.0, 16.0 / 255.0, 4.0 / 255.0, 1.0 / 255.0));
}

// XeGTAO_UnpackEdges.
vec4 horizonUnpackEdges(float packedValue) {
  uint bits = uint(packedValue * 255.5);
  vec4 edges = vec4(float((bits >> 6) & 3u), float((bits >> 4) & 3u), float((bits >> 2) & 3u), float(bits & 3u)) / 3.0;
  return clamp(edges, 0.0, 1.0);
}

// XeGTAO_FastSqrt (Drobot 2014's bit trick).
float horizonFastSqrt(float x) { return intBitsToFloat(0x1fbd1df5 + (floatBitsToInt(x) >> 1)); }

// XeGTAO_FastACos: [-1, 1] to [0, pi] (Lagarde's fit). Both results computed, then selected, as
// HLSL's ternary does: a GLSL ternary of expressions becomes a branch (5 % of the main pass on
// lavapipe).
float horizonFastAcos(float x) {
  float ax = abs(x);
  float result = (-0.156583 * ax + 1.570796) * horizonFastSqrt(1.0 - ax);
  float mirrored = 3.141593 - result;
  return x >= 0.0 ? result : mirrored;
}

// XeGTAO_FLOAT4_to_R8G8B8A8_UNORM and back.
uint horizonPackUnorm8x4(vec4 v) {
  uvec4 q = uvec4(clamp(v, 0.0, 1.0) * 255.0 + 0.5);
  return q.x | (q.y << 8) | (q.z << 16) | (q.w << 24);
}
vec4 horizonUnpackUnorm8x4(uint v) {
  return vec4(float(v & 0xffu), float((v >> 8) & 0xffu), float((v >> 16) & 0xffu), float(v >> 24)) / 255.0;
}

// XeGTAO's view space from this tool's (-z forward) and back: x and y keep or flip with the
// frame's signs, z flips. An involution: the same function converts both ways.
vec3 horizonFromToolView(vec3 v) { return vec3(v.xy * pc.viewAxisSigns, -v.z); }
