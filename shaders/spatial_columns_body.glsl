// Body of spatial_columns_<format>.comp (first dispatch of the spatial pass, see spatial_denoise.h):
// each pixel's vertical leg, 5 taps. Each variant defines AOR_AO_FORMAT (the AO image's format
// qualifier): a storage read needs the format at compile time because lavapipe lacks
// shaderStorageImageReadWithoutFormat, and imageLoad is much cheaper there than a sampler.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_control_flow_attributes : require
#include "spatial_denoise.h"

layout(local_size_x = kWorkgroupSize, local_size_y = kWorkgroupSize) in;
layout(push_constant, scalar) uniform Push { SpatialConstants pc; };
layout(set = 0, binding = 0, AOR_AO_FORMAT) uniform readonly image2D aoIn;  // R16F or RGBA16F (bent.xyz, visibility)
layout(set = 0, binding = 1, r32f) uniform readonly image2D viewDistance;
layout(set = 0, binding = 2) uniform writeonly image2D columnSum;     // sum of gy * path * ao, AO format
layout(set = 0, binding = 3) uniform writeonly image2D columnWeight;  // R16F: sum of gy * path (>= 1)

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= pc.size.x || pixel.y >= pc.size.y) return;
  float centreDistance = imageLoad(viewDistance, pixel).r;
  vec4 sum = imageLoad(aoIn, pixel);
  float weightSum = 1.0;
  [[unroll]] for (int direction = -1; direction <= 1; direction += 2) {
    float path = 1.0;
    float previous = centreDistance;
    [[unroll]] for (int k = 1; k <= kSpatialRadius; ++k) {
      // Distances past the edge repeat the edge (the path keeps walking); AO there weighs 0.
      int tapY = pixel.y + direction * k;
      ivec2 tap = ivec2(pixel.x, clamp(tapY, 0, pc.size.y - 1));
      float current = imageLoad(viewDistance, tap).r;
      path = spatialPathStep(path, previous, current);
      previous = current;
      float weight = tapY == tap.y ? kGaussian1D[k] * path : 0.0;
      sum += weight * imageLoad(aoIn, tap);
      weightSum += weight;
    }
  }
  imageStore(columnSum, pixel, sum);
  imageStore(columnWeight, pixel, vec4(weightSum));
}
