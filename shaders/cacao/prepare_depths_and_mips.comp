#version 450
// CACAO prepare depths with MIPs (medium and above): FFX_CACAO_Prepare{Native,Downsampled}DepthsAndMips.
// Each 8x8 workgroup writes 8x8 texels of MIP 0 of every layer, then reduces them in shared memory
// to MIPs 1-3 with FFX_CACAO_MipSmartAverage: at MIP 1 every thread averages one 2x2 block of one
// layer (its layer from its own 2x2 phase), at MIP 2 a quarter of them, at MIP 3 one per layer.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_control_flow_attributes : require
#include "cacao_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = kCacaoSpecDownsampled) const bool kDownsampled = false;
layout(constant_id = kCacaoSpecDepthMipLevels) const int kMipLevels = 4;  // bindings past the last level repeat it: not written
layout(set = 0, binding = 1) uniform sampler2D depthIn;
layout(set = 0, binding = 2, r16f) uniform writeonly image2DArray depthMip0;
layout(set = 0, binding = 3, r16f) uniform writeonly image2DArray depthMip1;
layout(set = 0, binding = 4, r16f) uniform writeonly image2DArray depthMip2;
layout(set = 0, binding = 5, r16f) uniform writeonly image2DArray depthMip3;

shared float scratch[4][8][8];

// size0: the layers' size (MIP 0, DeinterleavedDepthBufferDimensions); level k of the image is
// max(1, size0 >> k) as Vulkan sizes MIPs: the bounds without an imageSize query per store (each a
// texture-unit instruction on NVIDIA, six a thread against FidelityFX's one gather).
void storeIfInside(int level, ivec2 p, int layer, float value, ivec2 size0) {
  if (level >= kMipLevels) return;
  if (any(greaterThanEqual(p, max(size0 >> level, ivec2(1))))) return;
  ivec3 at = ivec3(p, layer);
  if (level == 0) imageStore(depthMip0, at, vec4(value));
  if (level == 1) imageStore(depthMip1, at, vec4(value));
  if (level == 2) imageStore(depthMip2, at, vec4(value));
  if (level == 3) imageStore(depthMip3, at, vec4(value));
}

void main() {
  CacaoConstants c = cacaoLayers[0];
  ivec2 tid = ivec2(gl_GlobalInvocationID.xy);
  ivec2 gtid = ivec2(gl_LocalInvocationID.xy);
  ivec2 size0 = ivec2(c.deinterleavedDepthBufferDimensions);
  vec4 phases = cacaoGatherPhases(depthIn, tid, kDownsampled, c.depthBufferInverseDimensions);
  AOR_UNROLL for (int layer = 0; layer < kCacaoLayers; ++layer) {
    float z = cacaoViewDepth(c, phases[layer]);
    scratch[layer][gtid.x][gtid.y] = z;
    storeIfInside(0, tid, layer, z, size0);
  }

  // gtid and tid are not negative: masks and shifts for FidelityFX's unsigned % 2 and / 2.
  ivec2 offset = gtid & 1;
  int layer = 2 * offset.y + offset.x;
  ivec2 at = gtid - offset;
  ivec2 outputCoord = tid >> 1;
  barrier();
  float avg = cacaoMipSmartAverage(vec4(scratch[layer][at.x][at.y], scratch[layer][at.x][at.y + 1],
                                        scratch[layer][at.x + 1][at.y], scratch[layer][at.x + 1][at.y + 1]),
                                   c.effectRadius);
  storeIfInside(1, outputCoord, layer, avg, size0);
  // In place, as FidelityFX: the block's first cell is read by this thread only, so no barrier
  // before the write (one barrier a level, as FidelityFX's).
  scratch[layer][at.x][at.y] = avg;

  AOR_UNROLL for (int level = 2; level <= 3; ++level) {
    int spacing = 1 << (level - 1);  // 2, then 4: the stride between the previous level's texels
    bool alive = all(equal(gtid & (2 * spacing - 1), offset));
    outputCoord >>= 1;
    barrier();
    if (alive) {
      avg = cacaoMipSmartAverage(vec4(scratch[layer][at.x][at.y], scratch[layer][at.x][at.y + spacing],
                                      scratch[layer][at.x + spacing][at.y], scratch[layer][at.x + spacing][at.y + spacing]),
                                 c.effectRadius);
      storeIfInside(level, outputCoord, layer, avg, size0);
      scratch[layer][at.x][at.y] = avg;
    }
  }
}
