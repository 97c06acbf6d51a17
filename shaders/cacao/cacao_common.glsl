// What CACAO's passes share on the GPU side (ffx_cacao.hlsl's helpers): the constant buffers,
// depth unpacking, view-space positions. Binding 0 of every pass is the four layers' constants;
// a pass over the layers picks its layer's by gl_WorkGroupID.z (FidelityFX binds one buffer per
// layer instead).
#include "cacao.h"

layout(set = 0, binding = 0, scalar) uniform CacaoConstantBuffers { CacaoConstants cacaoLayers[kCacaoLayers]; };

// FFX_CACAO_ScreenSpaceToViewSpaceDepth. Depth the R16F buffers cannot hold (the far plane of an
// infinite projection, invalid input) is stored as kCacaoMaxViewDepth instead of inf or NaN.
float cacaoViewDepth(CacaoConstants c, float screenDepth) {
  float z = c.depthUnpackConsts.x / (c.depthUnpackConsts.y - screenDepth);
  return z > 0.0 ? min(z, kCacaoMaxViewDepth) : kCacaoMaxViewDepth;  // NaN and z <= 0 fail the test
}

// FFX_CACAO_NDCToViewSpace (uv in [0, 1], origin top left) and FFX_CACAO_DepthBufferUVToViewSpace.
vec3 cacaoNdcToView(CacaoConstants c, vec2 pos, float viewDepth) {
  return vec3((c.ndcToViewMul * pos + c.ndcToViewAdd) * viewDepth, viewDepth);
}
vec3 cacaoDepthBufferUvToView(CacaoConstants c, vec2 pos, float viewDepth) {
  return vec3((c.depthBufferUvToViewMul * pos + c.depthBufferUvToViewAdd) * viewDepth, viewDepth);
}

// The layer a dispatch over the deinterleaved layers works on: z of the workgroup, except at
// lowest where only layers 0 and 3 exist (z = 0, 1).
int cacaoLayerOf(uint z, bool twoLayers) { return twoLayers ? int(z) * 3 : int(z); }

// The capture depth of the four phases of deinterleaved texel p, layer k's at [k] (phase
// (k % 2, k / 2)), clamped at the edge: native, one gather of the 2x2 block at its shared corner
// (as FidelityFX's GatherRed; at the corner, not a texel centre, so rounding cannot move the
// footprint; 0.8 -> 1.0x of four texelFetch's time on lavapipe); downsampled, the 4x4 block's
// even pixels by four nearest samples at their centres, clamped by the sampler (as FidelityFX's
// point-clamp samples; 0.8 -> 1.0x of four clamped texelFetch). invSize is the depth buffer's
// inverse size from the constants (DepthBufferInverseDimensions): a multiply instead of a
// textureSize query (a texture-unit instruction on NVIDIA) and divides; at a corner or a centre the
// coordinate's last bits cannot move the footprint, so the same texels are read.
vec4 cacaoGatherPhases(sampler2D depth, ivec2 p, bool downsampled, vec2 invSize) {
  // textureGather's x, y, z, w are texels (0, 1), (1, 1), (1, 0), (0, 0) of the footprint.
  if (!downsampled) return textureGather(depth, vec2(2 * p + 1) * invSize).wzxy;
  vec2 centre = vec2(4 * p) + 0.5;
  return vec4(textureLod(depth, centre * invSize, 0.0).x, textureLod(depth, (centre + vec2(2, 0)) * invSize, 0.0).x,
              textureLod(depth, (centre + vec2(0, 2)) * invSize, 0.0).x, textureLod(depth, (centre + vec2(2, 2)) * invSize, 0.0).x);
}
