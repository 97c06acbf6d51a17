// XeGTAO pass 3 (XeGTAO_Denoise): the edge-aware 3x3 blur, each thread two horizontally adjacent
// pixels from seven gathers. Built as denoise.comp (a pass before the last: the working term out,
// blur beta / 5) and denoise_last.comp (HORIZON_LAST_PASS: full beta, the term scaled back by 1.5
// and decoded as XeGTAO's consumer reads its 8-bit output, written as float for the shared blocks
// and the read-back).
layout(local_size_x = kHorizonWorkgroupSize, local_size_y = kHorizonWorkgroupSize) in;
layout(constant_id = kHorizonSpecBent) const bool kBent = false;

layout(set = 0, binding = 0) uniform usampler2D sourceAoTerm;  // R8_UINT (R32_UINT with bent normals), nearest, clamped
layout(set = 0, binding = 1) uniform sampler2D sourceEdges;    // R8_UNORM packed edges
layout(push_constant, scalar) uniform Push { HorizonConstants pc; };
#ifdef HORIZON_LAST_PASS
layout(set = 0, binding = 2) uniform writeonly image2D outputAo;  // R16F visibility, or RGBA16F bent.xyz + visibility
#else
layout(set = 0, binding = 2) uniform writeonly uimage2D outputAo;  // the working term again
#endif

#include "horizon_common.glsl"
#include "horizon_term.glsl"

// XeGTAO_DecodeGatherPartial.
void decodeQuad(uvec4 packedValues, out vec4 decoded[4]) {
  for (int i = 0; i < 4; ++i) decoded[i] = decodeTerm(packedValues[i]);
}

// XeGTAO_Output. The sky is left to the sky pass after the last denoise (sky.comp), as XeGTAO
// leaves it to the engine: every pass here blends and stores XeGTAO's own values at sky pixels.
void storeTerm(ivec2 pixel, vec4 term) {
  if (any(greaterThanEqual(pixel, pc.viewportSize))) return;
#ifdef HORIZON_LAST_PASS
  imageStore(outputAo, pixel, horizonEngineValue(term));
#else
  imageStore(outputAo, pixel, uvec4(horizonPackTerm(term, 1.0)));
#endif
}

void main() {
#ifdef HORIZON_LAST_PASS
  float blurAmount = pc.denoiseBlurBeta;
#else
  float blurAmount = pc.denoiseBlurBeta / 5.0;
#endif
  uvec2 base = gl_GlobalInvocationID.xy * uvec2(2u, 1u);
  // Gathers at the top-left corner of `base` (component order x, y, z, w = (-1,+0), (+0,+0),
  // (+0,-1), (-1,-1) from the gather's texel), shifted by their offsets.
  vec2 gatherCenter = vec2(base) * pc.viewportPixelSize;
  vec4 edgesQ0 = textureGather(sourceEdges, gatherCenter);
  vec4 edgesQ1 = textureGatherOffset(sourceEdges, gatherCenter, ivec2(2, 0));
  vec4 edgesQ2 = textureGatherOffset(sourceEdges, gatherCenter, ivec2(1, 2));
  vec4 visQ0[4], visQ1[4], visQ2[4], visQ3[4];
  decodeQuad(textureGather(sourceAoTerm, gatherCenter), visQ0);
  decodeQuad(textureGatherOffset(sourceAoTerm, gatherCenter, ivec2(2, 0)), visQ1);
  decodeQuad(textureGatherOffset(sourceAoTerm, gatherCenter, ivec2(0, 2)), visQ2);
  decodeQuad(textureGatherOffset(sourceAoTerm, gatherCenter, ivec2(2, 2)), visQ3);

  for (int side = 0; side < 2; ++side) {
    bool left = side == 0;
    vec4 edgesL = horizonUnpackEdges(left ? edgesQ0.x : edgesQ0.y);
    vec4 edgesT = horizonUnpackEdges(left ? edgesQ0.z : edgesQ1.w);
    vec4 edgesR = horizonUnpackEdges(left ? edgesQ1.x : edgesQ1.y);
    vec4 edgesB = horizonUnpackEdges(left ? edgesQ2.w : edgesQ2.z);
    vec4 edgesC = horizonUnpackEdges(left ? edgesQ0.y : edgesQ1.x);
    // Symmetric edges: each side also as its neighbour sees it.
    edgesC *= vec4(edgesL.y, edgesR.x, edgesT.w, edgesB.z);
    // A little leaking where three or four sides are edges (less aliasing).
    const float leakThreshold = 2.5, leakStrength = 0.5;
    float edginess = (clamp(4.0 - leakThreshold - dot(edgesC, vec4(1.0)), 0.0, 1.0) / (4.0 - leakThreshold)) * leakStrength;
    edgesC = clamp(edgesC + edginess, 0.0, 1.0);

    float weightTL = kHorizonDiagonalWeight * (edgesC.x * edgesL.z + edgesC.z * edgesT.x);
    float weightTR = kHorizonDiagonalWeight * (edgesC.z * edgesT.y + edgesC.y * edgesR.z);
    float weightBL = kHorizonDiagonalWeight * (edgesC.w * edgesB.x + edgesC.x * edgesL.w);
    float weightBR = kHorizonDiagonalWeight * (edgesC.y * edgesR.w + edgesC.w * edgesB.y);

    vec4 centre = left ? visQ0[1] : visQ1[0];
    vec4 valueL = left ? visQ0[0] : visQ0[1];
    vec4 valueT = left ? visQ0[2] : visQ1[3];
    vec4 valueR = left ? visQ1[0] : visQ1[1];
    vec4 valueB = left ? visQ2[2] : visQ3[3];
    vec4 valueTL = left ? visQ0[3] : visQ0[2];
    vec4 valueBR = left ? visQ3[3] : visQ3[2];
    vec4 valueTR = left ? visQ1[3] : visQ1[2];
    vec4 valueBL = left ? visQ2[3] : visQ2[2];

    // XeGTAO_AddSample, in its order.
    float sumWeight = blurAmount;
    vec4 sum = centre * sumWeight;
    sum += edgesC.x * valueL;  sumWeight += edgesC.x;
    sum += edgesC.y * valueR;  sumWeight += edgesC.y;
    sum += edgesC.z * valueT;  sumWeight += edgesC.z;
    sum += edgesC.w * valueB;  sumWeight += edgesC.w;
    sum += weightTL * valueTL; sumWeight += weightTL;
    sum += weightTR * valueTR; sumWeight += weightTR;
    sum += weightBL * valueBL; sumWeight += weightBL;
    sum += weightBR * valueBR; sumWeight += weightBR;
    storeTerm(ivec2(base) + ivec2(side, 0), sum / sumWeight);
  }
}
