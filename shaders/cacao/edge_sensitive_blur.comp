#version 450
// CACAO edge-sensitive blur: FFX_CACAO_EdgeSensitiveBlurN (N = blur_pass_count, 1..8). Each 16x16
// workgroup loads a 64x48 tile of one layer (4x3 pixels a thread), runs N 3x3 passes on it in
// shared memory, each weighting the four neighbours by the centre's unpacked edges, and writes
// the tile less N pixels on each side (so the tiles overlap by 2N). As FidelityFX's, the input is
// read with mirrored addressing and the values between passes are kept as 16-bit floats.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_control_flow_attributes : require
#include "cacao_common.glsl"

layout(local_size_x = kCacaoBlurWorkgroup, local_size_y = kCacaoBlurWorkgroup) in;
layout(constant_id = kCacaoSpecBlurPasses) const int kBlurPasses = 2;
layout(constant_id = kCacaoSpecHalf) const bool kTwoLayers = false;
layout(set = 0, binding = 1) uniform sampler2DArray ssaoIn;  // RG8: visibility, packed edges
layout(set = 0, binding = 2) uniform writeonly image2DArray ssaoOut;

const int kTileW = kCacaoBlurTileWidth * int(kCacaoBlurWorkgroup);   // 64
const int kTileH = kCacaoBlurTileHeight * int(kCacaoBlurWorkgroup);  // 48
// Pixel (x, y) of the tile at [x + 2][y + 1]: FidelityFX's halo of one packed pair left and right, a row above and below.
shared float front[kTileW + 4][kTileH + 2];
shared float back[kTileW + 4][kTileH + 2];

float toHalf(float v) { return unpackHalf2x16(packHalf2x16(vec2(v, 0.0))).x; }

int mirrorIndex(int i, int n) {
  int period = 2 * n;
  i = ((i % period) + period) % period;
  return i < n ? i : period - 1 - i;
}

// FFX_CACAO_CalcBlurredSampleF16_4 for one pixel.
float blurred(vec4 edges, float centre, float left, float right, float top, float bottom) {
  float sum = centre * 0.5, weight = 0.5;
  sum += left * edges.x;
  weight += edges.x;
  sum += right * edges.y;
  weight += edges.y;
  sum += top * edges.z;
  weight += edges.z;
  sum += bottom * edges.w;
  weight += edges.w;
  return sum / weight;
}

void main() {
  int layer = cacaoLayerOf(gl_WorkGroupID.z, kTwoLayers);
  CacaoConstants c = cacaoLayers[layer];
  ivec2 tid = ivec2(gl_LocalInvocationID.xy);
  ivec2 gid = ivec2(gl_WorkGroupID.xy);
  ivec2 imageCoord = gid * (ivec2(kTileW, kTileH) - 2 * kBlurPasses) + ivec2(kCacaoBlurTileWidth, kCacaoBlurTileHeight) * tid - kBlurPasses;
  ivec2 base = ivec2(kCacaoBlurTileWidth, kCacaoBlurTileHeight) * tid;  // the thread's first pixel in the tile
  ivec2 size = textureSize(ssaoIn, 0).xy;

  // The halo is never written by a load; zero it so no pass reads undefined memory.
  for (int i = int(gl_LocalInvocationIndex); i < (kTileW + 4) * (kTileH + 2); i += int(kCacaoBlurWorkgroup * kCacaoBlurWorkgroup)) {
    front[i / (kTileH + 2)][i % (kTileH + 2)] = 0.0;
    back[i / (kTileH + 2)][i % (kTileH + 2)] = 0.0;
  }
  barrier();

  vec4 edges[kCacaoBlurTileWidth][kCacaoBlurTileHeight];
  float packedEdges[kCacaoBlurTileWidth][kCacaoBlurTileHeight];
  AOR_UNROLL for (int y = 0; y < kCacaoBlurTileHeight; ++y)
    AOR_UNROLL for (int x = 0; x < kCacaoBlurTileWidth; ++x) {
      ivec2 p = imageCoord + ivec2(x, y);
      vec2 v = texelFetch(ssaoIn, ivec3(mirrorIndex(p.x, size.x), mirrorIndex(p.y, size.y), layer), 0).xy;
      front[base.x + x + 2][base.y + y + 1] = toHalf(v.x);
      packedEdges[x][y] = v.y;
      edges[x][y] = cacaoUnpackEdges(v.y, c.invSharpness);
    }
  barrier();

  AOR_UNROLL for (int pass = 0; pass < kBlurPasses; ++pass) {
    bool fromFront = pass % 2 == 0;
    float result[kCacaoBlurTileWidth][kCacaoBlurTileHeight];
    for (int y = 0; y < kCacaoBlurTileHeight; ++y)
      for (int x = 0; x < kCacaoBlurTileWidth; ++x) {
        int bx = base.x + x + 2, by = base.y + y + 1;
        if (fromFront) result[x][y] = blurred(edges[x][y], front[bx][by], front[bx - 1][by], front[bx + 1][by], front[bx][by - 1], front[bx][by + 1]);
        else result[x][y] = blurred(edges[x][y], back[bx][by], back[bx - 1][by], back[bx + 1][by], back[bx][by - 1], back[bx][by + 1]);
      }
    for (int y = 0; y < kCacaoBlurTileHeight; ++y)
      for (int x = 0; x < kCacaoBlurTileWidth; ++x) {
        if (fromFront) back[base.x + x + 2][base.y + y + 1] = toHalf(result[x][y]);
        else front[base.x + x + 2][base.y + y + 1] = toHalf(result[x][y]);
      }
    barrier();
  }

  AOR_UNROLL for (int y = 0; y < kCacaoBlurTileHeight; ++y)
    AOR_UNROLL for (int x = 0; x < kCacaoBlurTileWidth; ++x) {
      ivec2 local = base + ivec2(x, y);
      if (any(lessThan(local, ivec2(kBlurPasses))) || any(greaterThanEqual(local, ivec2(kTileW, kTileH) - kBlurPasses))) continue;
      ivec2 p = imageCoord + ivec2(x, y);
      if (any(greaterThanEqual(p, size))) continue;
      float v = kBlurPasses % 2 == 0 ? front[local.x + 2][local.y + 1] : back[local.x + 2][local.y + 1];
      imageStore(ssaoOut, ivec3(p, layer), vec4(v, packedEdges[x][y], 0.0, 0.0));
    }
}
