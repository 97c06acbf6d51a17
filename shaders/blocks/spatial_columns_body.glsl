// Body of spatial_columns_<format>.comp (first dispatch of the spatial pass, see spatial_denoise.h):
// each pixel's vertical leg, 5 taps. Each variant defines AOR_AO_FORMAT (the AO image's format
// qualifier): a storage read needs the format at compile time because lavapipe lacks
// shaderStorageImageReadWithoutFormat, and imageLoad is much cheaper there than a sampler.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_control_flow_attributes : require
#include "spatial_denoise.h"

// Each thread sums the vertical legs of kSpatialStrip pixels of one column: they share their
// taps, so the column's AO and distances are loaded once for the strip (kSpatialStrip + 4 rows)
// instead of five times per pixel, and each edge weight is computed once.
layout(local_size_x = kSpatialColumnsWorkgroupSize, local_size_y = kSpatialColumnsWorkgroupSize / kSpatialStrip) in;
layout(constant_id = kSpatialSpecHalfResolution) const bool kHalfResolution = false;
layout(push_constant, scalar) uniform Push { SpatialConstants pc; };  // size: the AO image's
layout(set = 0, binding = 0, AOR_AO_FORMAT) uniform readonly image2D aoIn;  // R16F or RGBA16F (bent.xyz, visibility)
layout(set = 0, binding = 1, r32f) uniform readonly image2D viewDistance;  // full resolution
layout(set = 0, binding = 2) uniform writeonly image2D columnSum;     // sum of gy * path * ao, AO format
// RG16F: x = sum of gy * path (>= 1; 0 marks a sky pixel), y = the edge weight to the pixel on the
// right (0 at the right border), so spatial needs no distance reads.
layout(set = 0, binding = 3) uniform writeonly image2D columnWeightAndEdge;

const int kWindow = kSpatialStrip + 2 * kSpatialRadius;  // rows the strip's taps touch

float loadDistance(ivec2 texel) { return imageLoad(viewDistance, kHalfResolution ? texel * 2 : texel).r; }

void main() {
  int x = int(gl_GlobalInvocationID.x);
  int firstRow = int(gl_WorkGroupID.y * kSpatialColumnsWorkgroupSize + gl_LocalInvocationID.y * kSpatialStrip);
  if (x >= pc.size.x || firstRow >= pc.size.y) return;
  // Rows past the edge repeat the edge's distance (the path keeps walking) and weigh 0.
  float distance[kWindow];
  vec4 ao[kWindow];
  bool inside[kWindow];
  [[unroll]] for (int i = 0; i < kWindow; ++i) {
    int row = firstRow - kSpatialRadius + i;
    ivec2 tap = ivec2(x, clamp(row, 0, pc.size.y - 1));
    inside[i] = row == tap.y;
    distance[i] = loadDistance(tap);
    ao[i] = imageLoad(aoIn, tap);
  }
  int right = min(x + 1, pc.size.x - 1);
  float edge[kWindow - 1];  // edge[i]: between rows i and i + 1 (depthEdgeWeight is symmetric)
  [[unroll]] for (int i = 0; i < kWindow - 1; ++i) edge[i] = depthEdgeWeight(distance[i], distance[i + 1]);
  [[unroll]] for (int s = 0; s < kSpatialStrip; ++s) {
    int centre = s + kSpatialRadius;
    vec4 sum = ao[centre];
    float weightSum = 1.0;
    [[unroll]] for (int direction = -1; direction <= 1; direction += 2) {  // up, then down, as spatial sums
      float path = 1.0;
      [[unroll]] for (int k = 1; k <= kSpatialRadius; ++k) {
        int tap = centre + direction * k;
        path *= edge[direction < 0 ? tap : tap - 1];
        float weight = inside[tap] ? kGaussian1D[k] * path : 0.0;
        sum += weight * ao[tap];
        weightSum += weight;
      }
    }
    ivec2 pixel = ivec2(x, firstRow + s);
    if (pixel.y < pc.size.y) {
      float rightEdge = right > x ? depthEdgeWeight(distance[centre], loadDistance(ivec2(right, pixel.y))) : 0.0;
      imageStore(columnSum, pixel, sum);
      imageStore(columnWeightAndEdge, pixel, vec4(distance[centre] > 0.0 ? weightSum : 0.0, rightEdge, 0.0, 0.0));
    }
  }
}
