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
layout(set = 0, binding = 1, AOR_AO_FORMAT) uniform readonly image2D columnSum;
layout(set = 0, binding = 2, rg16f) uniform readonly image2D columnWeightAndEdge;  // see spatial_columns_body.glsl
layout(set = 0, binding = 3) uniform writeonly image2D aoOut;

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= pc.size.x || pixel.y >= pc.size.y) return;
  vec4 sum = imageLoad(columnSum, pixel);
  vec2 centre = imageLoad(columnWeightAndEdge, pixel).xy;
  float weightSum = centre.x;
  [[unroll]] for (int direction = -1; direction <= 1; direction += 2) {
    float path = 1.0;
    float rightEdge = centre.y;  // the edge leaving the previous tap to the right
    [[unroll]] for (int k = 1; k <= kSpatialRadius; ++k) {
      int tapX = pixel.x + direction * k;
      ivec2 tap = ivec2(clamp(tapX, 0, pc.size.x - 1), pixel.y);
      vec2 tapWeightAndEdge = imageLoad(columnWeightAndEdge, tap).xy;
      // Walking right, the edge crossed is the previous tap's right edge; walking left, the tap's own.
      path *= direction > 0 ? rightEdge : tapWeightAndEdge.y;
      rightEdge = tapWeightAndEdge.y;
      float weight = tapX == tap.x ? kGaussian1D[k] * path : 0.0;
      sum += weight * imageLoad(columnSum, tap);
      weightSum += weight * tapWeightAndEdge.x;
    }
  }
  vec4 result = sum / weightSum;  // weightSum >= 1 unless the pixel is sky (0)
  bool sky = centre.x == 0.0;
  float len = kBent ? length(result.xyz) : 1.0;
  if (sky || !(len > 1e-6)) {  // sky: nothing to blur; a degenerate bent sum: the unblurred normal
    vec4 unblurred = imageLoad(aoIn, pixel);
    result = sky ? unblurred : vec4(unblurred.xyz, result.w);
  } else if (kBent) {
    result.xyz /= len;
  }
  imageStore(aoOut, pixel, result);
}
