#version 450
// CACAO bilateral upsample of the downsampled SSAO buffer (downsample=1):
// FFX_CACAO_UpscaleBilateral5x5Smart (high, highest: each half-resolution texel reinterleaved as
// FFX_CACAO_Apply does), ..._5x5NonSmart (low, medium: the four layers' point samples averaged)
// and ..._5x5Half (lowest: layers 0 and 3). An 8x8 workgroup fills 12x16 half-resolution texels
// (value and deinterleaved depth, as 16-bit floats) into shared memory; each thread then writes 2x2
// output pixels, a 5x5 Gaussian in distance times a Gaussian in view-depth difference.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_control_flow_attributes : require
#include "cacao_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = kCacaoSpecVariant) const int kVariant = kCacaoVariantSmart;
layout(set = 0, binding = 1) uniform sampler2DArray ssaoLinear;  // RG8, bilinear
layout(set = 0, binding = 2) uniform sampler2DArray ssaoPoint;   // the same, nearest
layout(set = 0, binding = 3) uniform sampler2D depthIn;          // the capture's depth
layout(set = 0, binding = 4) uniform sampler2DArray viewDepths;  // deinterleaved view depth, MIP 0
layout(set = 0, binding = 5, r8) uniform writeonly image2D aoOut;

const int kBufferW = 8 + 4, kBufferH = 8 + 4 + 4;
shared float bufferSsao[kBufferW][kBufferH];
shared float bufferDepth[kBufferW][kBufferH];

float toHalf(float v) { return unpackHalf2x16(packHalf2x16(vec2(v, 0.0))).x; }

float linearAt(vec2 uv, int layer) { return textureLod(ssaoLinear, vec3(uv, float(layer)), 0.0).x; }
float pointAt(vec2 uv, int layer) { return textureLod(ssaoPoint, vec3(uv, float(layer)), 0.0).x; }
float viewDepthAt(ivec2 p, int layer) {
  ivec2 last = textureSize(viewDepths, 0).xy - 1;
  return texelFetch(viewDepths, ivec3(clamp(p, ivec2(0), last), layer), 0).x;
}

// One texel of the half-resolution (reinterleaved) grid: its AO and its depth.
vec2 smartTexel(CacaoConstants c, ivec2 q) {
  int mx = q.x % 2, my = q.y % 2;
  int ic = mx + my * 2, ih = (1 - mx) + my * 2, iv = mx + (1 - my) * 2, id = (1 - mx) + (1 - my) * 2;
  vec2 centerVal = texelFetch(ssaoLinear, ivec3(q / 2, ic), 0).xy;
  vec4 edges = cacaoUnpackEdges(centerVal.y, c.invSharpness);
  float fmx = float(mx), fmy = float(my);
  float fmxe = edges.y - edges.x, fmye = edges.w - edges.z;
  vec2 p = vec2(q);
  float aoH = linearAt((p + vec2(fmx + fmxe - 0.5, 0.5 - fmy)) * 0.5 * c.ssaoBufferInverseDimensions, ih);
  float aoV = linearAt((p + vec2(0.5 - fmx, fmy - 0.5 + fmye)) * 0.5 * c.ssaoBufferInverseDimensions, iv);
  float aoD = linearAt((p + vec2(fmx - 0.5 + fmxe, fmy - 0.5 + fmye)) * 0.5 * c.ssaoBufferInverseDimensions, id);
  vec4 w = vec4(1.0, (edges.x + edges.y) * 0.5, (edges.z + edges.w) * 0.5, 0.0);
  w.w = (w.y + w.z) * 0.5;
  float ao = dot(vec4(centerVal.x, aoH, aoV, aoD), w) / dot(w, vec4(1.0));
  // As FidelityFX's (which advances its x before loading the depth): the depth of texel (q.x + 1) / 2.
  return vec2(ao, viewDepthAt(ivec2(q.x + 1, q.y) / 2, ic));
}

vec2 nonSmartTexel(CacaoConstants c, ivec2 q) {
  vec2 inv = c.ssaoBufferInverseDimensions;
  vec2 loc0 = (vec2(q / 2) + 0.5) * inv, loc1 = loc0, loc2 = loc0, loc3 = loc0;
  int phase = (q.y % 2) * 2 + (q.x % 2);
  if (kVariant == kCacaoVariantHalf) {
    if (phase == 0) loc1 -= 0.5 * inv;
    else if (phase == 1) { loc0.x += 0.5 * inv.x; loc1.y -= 0.5 * inv.y; }
    else if (phase == 2) { loc0.y += 0.5 * inv.y; loc1.x -= 0.5 * inv.x; }
    else loc0 += 0.5 * inv;
    return vec2((pointAt(loc0, 0) + pointAt(loc1, 3)) * 0.5, viewDepthAt(q / 2, (q.y % 2) * 3));
  }
  if (phase == 0) { loc1.x -= 0.5 * inv.x; loc2.y -= 0.5 * inv.y; loc3 -= 0.5 * inv; }
  else if (phase == 1) { loc0.x += 0.5 * inv.x; loc2 += vec2(0.5, -0.5) * inv; loc3.y -= 0.5 * inv.y; }
  else if (phase == 2) { loc0.y += 0.5 * inv.y; loc1 += vec2(-0.5, 0.5) * inv; loc3.x -= 0.5 * inv.x; }
  else { loc0 += 0.5 * inv; loc1.y += 0.5 * inv.y; loc2.x += 0.5 * inv.x; }
  float ao = (pointAt(loc0, 0) + pointAt(loc1, 1) + pointAt(loc2, 2) + pointAt(loc3, 3)) * 0.25;
  return vec2(ao, viewDepthAt(q / 2, phase));
}

void main() {
  CacaoConstants c = cacaoLayers[0];
  ivec2 gtid = ivec2(gl_LocalInvocationID.xy);
  ivec2 gid = ivec2(gl_WorkGroupID.xy);
  ivec2 tid = ivec2(gl_GlobalInvocationID.xy);
  ivec2 halfSize = 2 * ivec2(c.ssaoBufferDimensions);
  {
    int threadNum = (gtid.y * 8 + gtid.x) * 3;
    ivec2 bufferCoord = ivec2(threadNum % kBufferW, threadNum / kBufferW);
    ivec2 imageCoord = gid * 8 + bufferCoord - 2;
    AOR_UNROLL for (int i = 0; i < 3; ++i) {
      // FidelityFX reads outside the buffers at the top and left (D3D returns 0 there); clamped here.
      ivec2 q = clamp(imageCoord + ivec2(i, 0), ivec2(0), halfSize - 1);
      vec2 value = kVariant == kCacaoVariantSmart ? smartTexel(c, q) : nonSmartTexel(c, q);
      bufferSsao[bufferCoord.x + i][bufferCoord.y] = toHalf(value.x);
      bufferDepth[bufferCoord.x + i][bufferCoord.y] = toHalf(value.y);
    }
  }
  barrier();

  ivec2 full = 2 * tid;
  ivec2 last = textureSize(depthIn, 0) - 1;
  vec4 depths = vec4(cacaoViewDepth(c, texelFetch(depthIn, min(full + ivec2(0, 0), last), 0).x),
                     cacaoViewDepth(c, texelFetch(depthIn, min(full + ivec2(1, 0), last), 0).x),
                     cacaoViewDepth(c, texelFetch(depthIn, min(full + ivec2(0, 1), last), 0).x),
                     cacaoViewDepth(c, texelFetch(depthIn, min(full + ivec2(1, 1), last), 0).x));
  ivec2 centre = gtid + 2;
  const float epsilonWeight = 1e-3;
  float nearest = bufferSsao[centre.x][centre.y];
  vec4 totals = vec4(epsilonWeight * nearest);
  vec4 totalWeights = vec4(epsilonWeight);
  float distSigma = 1.0 / c.bilateralSimilarityDistanceSigma;
  float sigma = 1.0 / c.bilateralSigmaSquared;
  AOR_UNROLL for (int x = -2; x <= 2; ++x)
    AOR_UNROLL for (int y = -2; y <= 2; ++y) {
      float s = bufferSsao[centre.x + x][centre.y + y], d = bufferDepth[centre.x + x][centre.y + y];
      vec2 u = vec2(x) - vec2(0.0, 0.5);
      vec2 v1 = vec2(y), v2 = vec2(y) - vec2(0.5);
      u *= u;
      v1 *= v1;
      v2 *= v2;
      vec2 wx1 = exp(-(u + v1) * sigma), wx2 = exp(-(u + v2) * sigma);
      vec2 diff1 = depths.xy - d, diff2 = depths.zw - d;
      diff1 *= diff1;
      diff2 *= diff2;
      vec2 weight1 = wx1 * exp(-diff1 * distSigma), weight2 = wx2 * exp(-diff2 * distSigma);
      totals += s * vec4(weight1, weight2);
      totalWeights += vec4(weight1, weight2);
    }
  vec4 outputValues = totals / totalWeights;
  ivec2 size = ivec2(c.outputBufferDimensions);
  ivec2 offsets[4] = ivec2[4](ivec2(0, 0), ivec2(1, 0), ivec2(0, 1), ivec2(1, 1));
  AOR_UNROLL for (int k = 0; k < 4; ++k)
    if (all(lessThan(full + offsets[k], size))) imageStore(aoOut, full + offsets[k], vec4(outputValues[k]));
}
