#version 450
// CACAO apply at native resolution, reinterleaving the four layers into the output:
// FFX_CACAO_Apply (smart: the pixel's own layer plus its three neighbours' bilinear taps, pushed
// away from edges and weighted by them), FFX_CACAO_NonSmartApply (low: the four layers averaged)
// and FFX_CACAO_NonSmartHalfApply (lowest: layers 0 and 3).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "cacao_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = kCacaoSpecVariant) const int kVariant = kCacaoVariantSmart;
layout(set = 0, binding = 1) uniform sampler2DArray ssao;  // RG8: visibility, packed edges; bilinear, clamped
layout(set = 0, binding = 2, r8) uniform writeonly image2D aoOut;

float sampleLayer(vec2 uv, int layer) { return textureLod(ssao, vec3(uv, float(layer)), 0.0).x; }

float smartApply(CacaoConstants c, ivec2 coord) {
  vec2 inPos = vec2(coord);
  int mx = coord.x % 2, my = coord.y % 2;
  int ic = mx + my * 2, ih = (1 - mx) + my * 2, iv = mx + (1 - my) * 2, id = (1 - mx) + (1 - my) * 2;
  vec2 centerVal = texelFetch(ssao, ivec3(coord / 2, ic), 0).xy;
  float ao = centerVal.x;
  vec4 edges = cacaoUnpackEdges(centerVal.y, c.invSharpness);
  float fmx = float(mx), fmy = float(my);
  float fmxe = edges.y - edges.x, fmye = edges.w - edges.z;
  vec2 uvH = (inPos + vec2(fmx + fmxe - 0.5, 0.5 - fmy)) * 0.5 * c.ssaoBufferInverseDimensions;
  vec2 uvV = (inPos + vec2(0.5 - fmx, fmy - 0.5 + fmye)) * 0.5 * c.ssaoBufferInverseDimensions;
  vec2 uvD = (inPos + vec2(fmx - 0.5 + fmxe, fmy - 0.5 + fmye)) * 0.5 * c.ssaoBufferInverseDimensions;
  float aoH = sampleLayer(uvH, ih), aoV = sampleLayer(uvV, iv), aoD = sampleLayer(uvD, id);
  vec4 blendWeights;
  blendWeights.x = 1.0;
  blendWeights.y = (edges.x + edges.y) * 0.5;
  blendWeights.z = (edges.z + edges.w) * 0.5;
  blendWeights.w = (blendWeights.y + blendWeights.z) * 0.5;
  return dot(vec4(ao, aoH, aoV, aoD), blendWeights) / dot(blendWeights, vec4(1.0));
}

void main() {
  CacaoConstants c = cacaoLayers[0];
  ivec2 coord = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(vec2(coord), c.outputBufferDimensions))) return;
  float ao;
  if (kVariant == kCacaoVariantSmart) {
    ao = smartApply(c, coord);
  } else {
    vec2 inUv = vec2(coord) * c.outputBufferInverseDimensions;  // FidelityFX's: the pixel's corner, not its centre
    if (kVariant == kCacaoVariantNonSmart) ao = (sampleLayer(inUv, 0) + sampleLayer(inUv, 1) + sampleLayer(inUv, 2) + sampleLayer(inUv, 3)) * 0.25;
    else ao = (sampleLayer(inUv, 0) + sampleLayer(inUv, 3)) * 0.5;
  }
  imageStore(aoOut, coord, vec4(ao));
}
