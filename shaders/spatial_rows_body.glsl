// Body of spatial_denoise_<format>.comp (second dispatch of the spatial pass, see
// spatial_denoise.h): the horizontal leg along the centre row, combining five column sums, then
// the normalisation. Each variant defines AOR_AO_FORMAT, as in spatial_columns_body.glsl.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_control_flow_attributes : require
#include "spatial_denoise.h"

layout(local_size_x = kWorkgroupSize, local_size_y = kWorkgroupSize) in;
layout(constant_id = kSpatialSpecBent) const bool kBent = true;
layout(push_constant, scalar) uniform Push { SpatialConstants pc; };
layout(set = 0, binding = 0, AOR_AO_FORMAT) uniform readonly image2D aoIn;   // the unblurred AO
layout(set = 0, binding = 1, r32f) uniform readonly image2D viewDistance;
layout(set = 0, binding = 2, AOR_AO_FORMAT) uniform readonly image2D columnSum;
layout(set = 0, binding = 3, r16f) uniform readonly image2D columnWeight;
layout(set = 0, binding = 4) uniform writeonly image2D aoOut;

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= pc.size.x || pixel.y >= pc.size.y) return;
  vec4 centreValue = imageLoad(aoIn, pixel);
  float centreDistance = imageLoad(viewDistance, pixel).r;
  vec4 sum = imageLoad(columnSum, pixel);
  float weightSum = imageLoad(columnWeight, pixel).r;
  [[unroll]] for (int direction = -1; direction <= 1; direction += 2) {
    float path = 1.0;
    float previous = centreDistance;
    [[unroll]] for (int k = 1; k <= kSpatialRadius; ++k) {
      int tapX = pixel.x + direction * k;
      ivec2 tap = ivec2(clamp(tapX, 0, pc.size.x - 1), pixel.y);
      float current = imageLoad(viewDistance, tap).r;
      path = spatialPathStep(path, previous, current);
      previous = current;
      float weight = tapX == tap.x ? kGaussian1D[k] * path : 0.0;
      sum += weight * imageLoad(columnSum, tap);
      weightSum += weight * imageLoad(columnWeight, tap).r;
    }
  }
  vec4 result = sum / weightSum;  // weightSum >= 1: the centre tap always counts
  if (kBent) {
    float len = length(result.xyz);
    result.xyz = len > 1e-6 ? result.xyz / len : centreValue.xyz;
  }
  imageStore(aoOut, pixel, centreDistance <= 0.0 ? centreValue : result);  // sky: nothing to blur
}
