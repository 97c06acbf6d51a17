#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "spatial_denoise.h"

layout(local_size_x = kWorkgroupSize, local_size_y = kWorkgroupSize) in;
layout(constant_id = kSpatialSpecBent) const bool kBent = true;
layout(push_constant, scalar) uniform Push { SpatialConstants pc; };
layout(set = 0, binding = 0) uniform sampler2D aoIn;          // R16F or RGBA16F (bent.xyz, visibility)
layout(set = 0, binding = 1) uniform sampler2D viewDistance;
layout(set = 0, binding = 2) uniform writeonly image2D aoOut;

float distanceAt(ivec2 p) {
  return texelFetch(viewDistance, clamp(p, ivec2(0), pc.size - 1), 0).r;
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= pc.size.x || pixel.y >= pc.size.y) return;
  vec4 centreValue = texelFetch(aoIn, pixel, 0);
  if (distanceAt(pixel) <= 0.0) {  // sky: nothing to blur
    imageStore(aoOut, pixel, centreValue);
    return;
  }
  // Path weights along the centre row (horizontal leg), accumulated outward from the centre.
  float rowDistance[2 * kSpatialRadius + 1];
  for (int dx = -kSpatialRadius; dx <= kSpatialRadius; ++dx) rowDistance[dx + kSpatialRadius] = distanceAt(pixel + ivec2(dx, 0));
  float rowPath[2 * kSpatialRadius + 1];
  rowPath[kSpatialRadius] = 1.0;
  for (int k = 1; k <= kSpatialRadius; ++k) {
    rowPath[kSpatialRadius + k] = rowPath[kSpatialRadius + k - 1] * depthEdgeWeight(rowDistance[kSpatialRadius + k - 1], rowDistance[kSpatialRadius + k]);
    rowPath[kSpatialRadius - k] = rowPath[kSpatialRadius - k + 1] * depthEdgeWeight(rowDistance[kSpatialRadius - k + 1], rowDistance[kSpatialRadius - k]);
  }

  vec4 sum = vec4(0.0);
  float weightSum = 0.0;
  for (int dx = -kSpatialRadius; dx <= kSpatialRadius; ++dx) {
    // Vertical leg at the target column, in both directions from the centre row.
    for (int direction = -1; direction <= 1; direction += 2) {
      float path = rowPath[dx + kSpatialRadius];
      float previous = rowDistance[dx + kSpatialRadius];
      for (int k = (direction < 0 ? 0 : 1); k <= kSpatialRadius; ++k) {
        ivec2 tap = pixel + ivec2(dx, direction * k);
        if (k > 0) {
          float current = distanceAt(tap);
          path *= depthEdgeWeight(previous, current);
          previous = current;
        }
        bool inside = tap.x >= 0 && tap.y >= 0 && tap.x < pc.size.x && tap.y < pc.size.y;
        float weight = inside ? spatialGaussian(dx, direction * k) * path : 0.0;
        if (weight > 0.0) {
          sum += weight * texelFetch(aoIn, tap, 0);
          weightSum += weight;
        }
      }
    }
  }
  vec4 result = sum / weightSum;  // weightSum >= 1: the centre tap always counts
  if (kBent) {
    float len = length(result.xyz);
    result.xyz = len > 1e-6 ? result.xyz / len : centreValue.xyz;
  }
  imageStore(aoOut, pixel, result);
}
