#version 450
// --debug views of the deinterleaved buffers: the four layers of one level tiled 2x2 (layer k at
// tile (k % 2, k / 2)) into one image, every channel kept; a layer CACAO does not write (1 and 2
// at lowest) is left zero.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "cacao.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = kCacaoSpecLayerMask) const int kLayerMask = 15;
layout(constant_id = kCacaoSpecFirstChannel) const int kFirstChannel = 0;  // 1: green first (the packed edges)
layout(set = 0, binding = 0) uniform sampler2DArray layers;
layout(set = 0, binding = 1, rgba16f) uniform writeonly image2D tiled;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 layerSize = textureSize(layers, 0).xy;
  if (any(greaterThanEqual(p, 2 * layerSize))) return;
  ivec2 tile = p / layerSize;
  int layer = tile.x + 2 * tile.y;
  vec4 value = ((kLayerMask >> layer) & 1) != 0 ? texelFetch(layers, ivec3(p - tile * layerSize, layer), 0) : vec4(0.0);
  imageStore(tiled, p, kFirstChannel == 1 ? value.yxzw : value);
}
