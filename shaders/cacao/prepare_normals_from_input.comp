#version 450
// CACAO prepare normals from the capture's: FFX_CACAO_Prepare{Native,Downsampled}NormalsFromInputNormals.
// Layer k gets the normal of 2x2 phase (k % 2, k / 2) (native; every second pixel downsampled),
// unpacked and turned into CACAO's view space by NormalsWorldToViewspaceMatrix (FFX_CACAO_Prepare_LoadNormal).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_control_flow_attributes : require
#include "cacao_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = kCacaoSpecDownsampled) const bool kDownsampled = false;
layout(set = 0, binding = 1) uniform sampler2D normalsIn;  // RGBA16F world normals (sky: 0)
layout(set = 0, binding = 2, rgba8_snorm) uniform writeonly image2DArray normalsOut;  // RGBA8_SNORM: the format known to the compiler

void main() {
  CacaoConstants c = cacaoLayers[0];
  ivec2 tid = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(vec2(tid), c.ssaoBufferDimensions))) return;
  int step = kDownsampled ? 2 : 1;
  ivec2 base = (kDownsampled ? 4 : 2) * tid;
  // The normals are the output's size (OutputBufferDimensions): the clamp without a textureSize
  // query (a texture-unit instruction on NVIDIA, one more to the four fetches).
  ivec2 last = ivec2(c.outputBufferDimensions) - 1;
  AOR_UNROLL for (int layer = 0; layer < kCacaoLayers; ++layer) {
    ivec2 q = min(base + step * ivec2(layer % 2, layer / 2), last);
    vec3 n = texelFetch(normalsIn, q, 0).xyz * c.normalsUnpackMul + c.normalsUnpackAdd;
    n = mat3(c.normalsWorldToViewspaceMatrix) * n;
    imageStore(normalsOut, ivec3(tid, layer), vec4(n, 1.0));
  }
}
