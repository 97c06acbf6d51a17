#version 450
// CACAO prepare depths without MIPs: FFX_CACAO_Prepare{Native,Downsampled}Depths (low) and
// FFX_CACAO_Prepare{Native,Downsampled}DepthsHalf (lowest: layers 0 and 3 only). Each thread
// writes one texel of each layer: the 2x2 phases of a 2x2 block (native) or of a 4x4 block's
// even pixels (downsampled), as view depth (cacaoGatherPhases).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_control_flow_attributes : require
#include "cacao_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = kCacaoSpecDownsampled) const bool kDownsampled = false;
layout(constant_id = kCacaoSpecHalf) const bool kHalf = false;
layout(set = 0, binding = 1) uniform sampler2D depthIn;  // the capture's depth, nearest, clamped
layout(set = 0, binding = 2, r16f) uniform writeonly image2DArray depthsOut;

void main() {
  CacaoConstants c = cacaoLayers[0];
  ivec2 tid = ivec2(gl_GlobalInvocationID.xy);
  // FidelityFX stores from every thread and leaves the partial workgroups past the layers' edge to
  // D3D, which drops writes outside a texture; in Vulkan they are undefined, so those threads
  // compute (the clamped gather reads inside the capture) and skip only their stores. Each store
  // under the test instead of an early return: 1.009-1.018 -> 1.000 of FidelityFX's time at low
  // native on an H200 (20 ABBA pairs; FidelityFX has no test at all).
  bool inside = all(lessThan(vec2(tid), c.deinterleavedDepthBufferDimensions));
  // Layer k holds phase (k % 2, k / 2), clamped at the edge as the point-clamp sampler is.
  vec4 phases;
  if (kHalf && !kDownsampled) {
    // FFX_CACAO_PrepareNativeDepthsHalf loads only the two texels it keeps (phases (0, 0), (1, 1)):
    // 1.012 -> 0.995 of FidelityFX's time on an H200 against one gather of all four.
    vec2 topLeft = vec2(2 * tid) + 0.5;
    phases.x = textureLod(depthIn, topLeft * c.depthBufferInverseDimensions, 0.0).x;
    phases.w = textureLod(depthIn, (topLeft + 1.0) * c.depthBufferInverseDimensions, 0.0).x;
  } else {
    phases = cacaoGatherPhases(depthIn, tid, kDownsampled, c.depthBufferInverseDimensions);
  }
  AOR_UNROLL for (int layer = 0; layer < kCacaoLayers; ++layer) {
    if (kHalf && (layer == 1 || layer == 2)) continue;  // discarded at lowest: top right, bottom left
    if (inside) imageStore(depthsOut, ivec3(tid, layer), vec4(cacaoViewDepth(c, phases[layer])));
  }
}
