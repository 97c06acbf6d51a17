// Body of spatial_denoise_<format>.comp: each variant defines AOR_AO_FORMAT (the AO image's
// format qualifier) and includes this. A storage read needs the format at compile time because
// lavapipe lacks shaderStorageImageReadWithoutFormat; imageLoad is much cheaper there than a
// sampler texelFetch and returns the same texel.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_control_flow_attributes : require
#include "spatial_denoise.h"

layout(local_size_x = kWorkgroupSize, local_size_y = kWorkgroupSize) in;
layout(constant_id = kSpatialSpecBent) const bool kBent = true;
layout(push_constant, scalar) uniform Push { SpatialConstants pc; };
layout(set = 0, binding = 0, AOR_AO_FORMAT) uniform readonly image2D aoIn;  // R16F or RGBA16F (bent.xyz, visibility)
layout(set = 0, binding = 1, r32f) uniform readonly image2D viewDistance;  // storage read: cheaper than a sampler on lavapipe
layout(set = 0, binding = 2) uniform writeonly image2D aoOut;

// The 5x5 blur, separated. A tap's weight is gx(dx) * gy(dy) * rowPath(dx) * columnPath(dx, dy):
// the Gaussian is separable, and the vertical leg of the path starts on the centre row at the tap's
// column, so it depends on that column pixel alone, not on the centre. Step 1 sums each column
// pixel's vertical leg once (5 taps), step 2 combines five of those per pixel along the row:
// 10 taps per pixel instead of 25, same weights (up to float rounding).
const int kGroup = int(kWorkgroupSize);
const int kTile = kGroup + 2 * kSpatialRadius;  // the workgroup plus its apron
const float kGaussian1D[kSpatialRadius + 1] = float[](1.0, exp(-1.0 / (2.0 * kSpatialSigma * kSpatialSigma)),
                                                      exp(-4.0 / (2.0 * kSpatialSigma * kSpatialSigma)));

// Inputs loaded once per workgroup; distances clamped to the edge like a per-pixel fetch would be.
// AO outside the image is never used: such taps weigh 0.
shared float tileDistance[kTile][kTile];
shared vec4 tileAo[kTile][kTile];
// Step 1 per (workgroup row, tile column): sum of gy * columnPath * ao, and of gy * columnPath.
shared vec4 columnSum[kGroup][kTile];
shared float columnWeight[kGroup][kTile];

void loadTile(ivec2 origin) {
  for (int i = int(gl_LocalInvocationIndex); i < kTile * kTile; i += kGroup * kGroup) {
    ivec2 t = ivec2(i % kTile, i / kTile);
    ivec2 p = clamp(origin + t, ivec2(0), pc.size - 1);
    tileDistance[t.y][t.x] = imageLoad(viewDistance, p).r;
    tileAo[t.y][t.x] = imageLoad(aoIn, p);
  }
}

// Vertical leg at tile column x, centre row y (tile coordinates), image row imageY.
void sumColumn(int x, int y, int imageY) {
  vec4 sum = vec4(0.0);
  float weightSum = 0.0;
  [[unroll]] for (int direction = -1; direction <= 1; direction += 2) {
    float path = 1.0;
    float previous = tileDistance[y][x];
    [[unroll]] for (int k = (direction < 0 ? 0 : 1); k <= kSpatialRadius; ++k) {
      int ty = y + direction * k;
      if (k > 0) {
        float current = tileDistance[ty][x];
        path *= depthEdgeWeight(previous, current);
        previous = current;
      }
      int tapY = imageY + direction * k;
      float weight = (tapY >= 0 && tapY < pc.size.y) ? kGaussian1D[k] * path : 0.0;
      sum += weight * tileAo[ty][x];
      weightSum += weight;
    }
  }
  columnSum[y - kSpatialRadius][x] = sum;
  columnWeight[y - kSpatialRadius][x] = weightSum;
}

void main() {
  ivec2 origin = ivec2(gl_WorkGroupID.xy) * kGroup - kSpatialRadius;
  loadTile(origin);
  barrier();
  for (int i = int(gl_LocalInvocationIndex); i < kGroup * kTile; i += kGroup * kGroup) {
    int row = i / kTile;
    sumColumn(i % kTile, row + kSpatialRadius, origin.y + row + kSpatialRadius);
  }
  barrier();

  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= pc.size.x || pixel.y >= pc.size.y) return;
  ivec2 c = pixel - origin;  // centre in the tile
  vec4 centreValue = tileAo[c.y][c.x];
  if (tileDistance[c.y][c.x] <= 0.0) {  // sky: nothing to blur
    imageStore(aoOut, pixel, centreValue);
    return;
  }
  int row = c.y - kSpatialRadius;
  vec4 sum = columnSum[row][c.x];
  float weightSum = columnWeight[row][c.x];
  // Horizontal leg along the centre row, outward in both directions.
  [[unroll]] for (int direction = -1; direction <= 1; direction += 2) {
    float path = 1.0;
    float previous = tileDistance[c.y][c.x];
    [[unroll]] for (int k = 1; k <= kSpatialRadius; ++k) {
      int tx = c.x + direction * k;
      float current = tileDistance[c.y][tx];
      path *= depthEdgeWeight(previous, current);
      previous = current;
      int tapX = pixel.x + direction * k;
      float weight = (tapX >= 0 && tapX < pc.size.x) ? kGaussian1D[k] * path : 0.0;
      sum += weight * columnSum[row][tx];
      weightSum += weight * columnWeight[row][tx];
    }
  }
  vec4 result = sum / weightSum;  // weightSum >= 1: the centre tap always counts
  if (kBent) {
    float len = length(result.xyz);
    result.xyz = len > 1e-6 ? result.xyz / len : centreValue.xyz;
  }
  imageStore(aoOut, pixel, result);
}
