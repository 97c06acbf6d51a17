#version 450
// CACAO edge-sensitive blur: FFX_CACAO_EdgeSensitiveBlurN (N = blur_pass_count, 1..8). Each 16x16
// workgroup loads a 64x48 tile of one layer (4x3 pixels a thread), runs N 3x3 passes on it in
// shared memory, each weighting the four neighbours by the centre's unpacked edges, and writes
// the tile less N pixels on each side (so the tiles overlap by 2N). As FidelityFX's, the input is
// read with mirrored addressing and the values between passes are kept as 16-bit floats, two
// horizontally adjacent pixels packed in one uint of shared memory (half the shared loads and
// stores of one float a pixel: 0.75 -> 0.87 of FidelityFX's time on lavapipe, output unchanged).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_control_flow_attributes : require
#include "cacao_common.glsl"

layout(local_size_x = kCacaoBlurWorkgroup, local_size_y = kCacaoBlurWorkgroup) in;
layout(constant_id = kCacaoSpecBlurPasses) const int kBlurPasses = 2;
layout(constant_id = kCacaoSpecHalf) const bool kTwoLayers = false;
layout(set = 0, binding = 1) uniform sampler2DArray ssaoIn;  // RG8: visibility, packed edges
layout(set = 0, binding = 2, rg8) uniform writeonly image2DArray ssaoOut;

const int kTileW = kCacaoBlurTileWidth * int(kCacaoBlurWorkgroup);   // 64
const int kTileH = kCacaoBlurTileHeight * int(kCacaoBlurWorkgroup);  // 48
const int kPairsW = kTileW / 2 + 2, kRowsH = kTileH + 2;  // FidelityFX's halo: one pair left and right, a row above and below
// Pixels (2i, y) and (2i + 1, y) of the tile, as packHalf2x16, at [i + 1][y + 1].
shared uint front[kPairsW][kRowsH];
shared uint back[kPairsW][kRowsH];

// The mirrored address of pixel i in a layer n pixels wide, as FidelityFX's mirror sampler. Its
// periodic form needs two signed % by a divisor known only at run time, which lavapipe turns into
// one scalar division a lane (x86 has no vector integer division); one reflection on each side
// gives the same index for i in [-2n, 2n), and the pixels that reach a stored one lie in
// [-8, n + 8) (at most 8 passes), inside that range once n >= 8. Beyond it (the far side of the
// last tile, whose pixels reach no stored one) the index is held at 0 so that every fetch stays
// inside the layer. Layers under 8 pixels a side take the periodic form, chosen when the pipeline
// is made (a run-time branch on the size put the native blur at 1.02-1.04 of FidelityFX's time on
// an H200; without it 0.70-0.75). Together with the stores below: the blur 0.89-0.99 of
// FidelityFX's time on lavapipe where it was 1.06-1.3 (output unchanged).
layout(constant_id = kCacaoSpecSmallLayer) const bool kSmallLayer = false;
int mirrorIndex(int i, int n) {
  if (kSmallLayer) {
    int period = 2 * n;
    i = ((i % period) + period) % period;
    return i < n ? i : period - 1 - i;
  }
  int m = max(i, -1 - i);
  return max(min(m, 2 * n - 1 - m), 0);
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

// One 3x3 pass over the thread's 4x3 pixels, from one buffer into the other (FidelityFX's loop body).
#define CACAO_BLUR_PASS(from, to)                                                                        \
  AOR_UNROLL for (int y = 0; y < kCacaoBlurTileHeight; ++y) {                                           \
    ivec2 q = pair + ivec2(0, y);                                                                       \
    vec4 centre = vec4(unpackHalf2x16(from[q.x][q.y]), unpackHalf2x16(from[q.x + 1][q.y]));             \
    vec4 top = vec4(unpackHalf2x16(from[q.x][q.y - 1]), unpackHalf2x16(from[q.x + 1][q.y - 1]));        \
    vec4 bottom = vec4(unpackHalf2x16(from[q.x][q.y + 1]), unpackHalf2x16(from[q.x + 1][q.y + 1]));     \
    vec4 left = vec4(unpackHalf2x16(from[q.x - 1][q.y]).y, centre.xyz);                                 \
    vec4 right = vec4(centre.yzw, unpackHalf2x16(from[q.x + 2][q.y]).x);                                \
    vec4 r;                                                                                             \
    AOR_UNROLL for (int x = 0; x < kCacaoBlurTileWidth; ++x)                                            \
      r[x] = blurred(edges[x][y], centre[x], left[x], right[x], top[x], bottom[x]);                     \
    to[q.x][q.y] = packHalf2x16(r.xy);                                                                  \
    to[q.x + 1][q.y] = packHalf2x16(r.zw);                                                              \
  }

void main() {
  int layer = cacaoLayerOf(gl_WorkGroupID.z, kTwoLayers);
  CacaoConstants c = cacaoLayers[layer];
  ivec2 tid = ivec2(gl_LocalInvocationID.xy);
  ivec2 gid = ivec2(gl_WorkGroupID.xy);
  ivec2 imageCoord = gid * (ivec2(kTileW, kTileH) - 2 * kBlurPasses) + ivec2(kCacaoBlurTileWidth, kCacaoBlurTileHeight) * tid - kBlurPasses;
  ivec2 base = ivec2(kCacaoBlurTileWidth, kCacaoBlurTileHeight) * tid;  // the thread's first pixel in the tile
  ivec2 pair = ivec2(base.x / 2, base.y) + 1;                           // its first pair in the buffers
  ivec2 size = ivec2(c.ssaoBufferDimensions);  // from the constants, as FidelityFX's (no size query)

  // The halo (the pair column each side, the rows above and below) is not written, as in
  // FidelityFX: pass k reads it only for the tile's outermost pixels, whose values spread k - 1
  // pixels inwards, and the stores below leave out the N pixels on each side, so no stored pixel
  // depends on it (the output is the same as with the halo zeroed, which cost 2 shared stores a
  // thread).

  vec4 edges[kCacaoBlurTileWidth][kCacaoBlurTileHeight];
  float packedEdges[kCacaoBlurTileWidth][kCacaoBlurTileHeight];
  AOR_UNROLL for (int y = 0; y < kCacaoBlurTileHeight; ++y) {
    vec4 v;
    AOR_UNROLL for (int x = 0; x < kCacaoBlurTileWidth; ++x) {
      ivec2 p = imageCoord + ivec2(x, y);
      vec2 t = texelFetch(ssaoIn, ivec3(mirrorIndex(p.x, size.x), mirrorIndex(p.y, size.y), layer), 0).xy;
      v[x] = t.x;
      packedEdges[x][y] = t.y;
      edges[x][y] = cacaoUnpackEdges(t.y, c.invSharpness);
    }
    front[pair.x][pair.y + y] = packHalf2x16(v.xy);
    front[pair.x + 1][pair.y + y] = packHalf2x16(v.zw);
  }
  barrier();

  // FidelityFX's loop runs the passes two at a time (front to back, back to front).
  AOR_UNROLL for (int pass = 0; pass < kBlurPasses; ++pass) {
    if (pass % 2 == 0) {
      CACAO_BLUR_PASS(front, back)
    } else {
      CACAO_BLUR_PASS(back, front)
    }
    barrier();
  }

  // The stores as FidelityFX's: a row test, the row's two words read once, a column test a pixel
  // (the image-size test folded into both).
  AOR_UNROLL for (int y = 0; y < kCacaoBlurTileHeight; ++y) {
    int ly = base.y + y;
    if (kBlurPasses <= ly && ly < kTileH - kBlurPasses && imageCoord.y + y < size.y) {
      ivec2 q = pair + ivec2(0, y);
      vec4 v = kBlurPasses % 2 == 0 ? vec4(unpackHalf2x16(front[q.x][q.y]), unpackHalf2x16(front[q.x + 1][q.y]))
                                    : vec4(unpackHalf2x16(back[q.x][q.y]), unpackHalf2x16(back[q.x + 1][q.y]));
      AOR_UNROLL for (int x = 0; x < kCacaoBlurTileWidth; ++x) {
        int lx = base.x + x;
        if (kBlurPasses <= lx && lx < kTileW - kBlurPasses && imageCoord.x + x < size.x)
          imageStore(ssaoOut, ivec3(imageCoord + ivec2(x, y), layer), vec4(v[x], packedEdges[x][y], 0.0, 0.0));
      }
    }
  }
}
