#ifndef AOR_SPATIAL_DENOISE_H
#define AOR_SPATIAL_DENOISE_H
// Pass 2 of seed 000: 5x5 bilateral blur, Gaussian sigma 1.5, with edge weights multiplied along a
// grid path from the centre (horizontal leg first, then vertical) so no tap tunnels through an edge.
//
// Run as two dispatches (spatial_columns, then spatial): a tap's weight is
// gx(dx) * gy(dy) * rowPath(dx) * columnPath(dx, dy), the Gaussian is separable, and the vertical
// leg of the path starts on the centre row at the tap's column, so it depends on that column pixel
// alone. spatial_columns sums each pixel's vertical leg once (5 taps: sum of gy * columnPath * ao
// and of gy * columnPath) and stores the edge weight to its right neighbour; spatial combines five
// of those along the row: 10 image reads per pixel instead of 25 taps and their distances, the
// seed's weights exactly (up to float rounding and the half-float column sums and edge weights).
// Deviation from the seed's single pass, on purpose: a shared-memory tile would do the same in one
// dispatch, but on a CPU device (lavapipe) every shared-memory access with a per-thread index is a
// scalar load per lane behind a branch; image reads are vector gathers. Two image-only dispatches
// took spatial from 14.2 to 6.0 ms at 640x360 there (bench/RESULTS.md).
#include "../common/common.h"
#include "../common/shared_begin.h"

AOR_CONST int kSpatialSpecBent = 0;
// spatial_columns: the AO is at half resolution (half_res=1), so texel t's distance is pixel 2t's.
// The blur itself is the same 5x5 over texels: twice the footprint in pixels, as seed 001 blurs
// its half-resolution AO before upsampling.
AOR_CONST int kSpatialSpecHalfResolution = 1;
AOR_CONST int kSpatialRadius = 2;          // 5x5
AOR_CONST float kSpatialSigma = 1.5f;
AOR_CONST int kSpatialStrip = 4;          // pixels per spatial_columns thread (a column strip)
// Pixels per side of a spatial_columns workgroup (a multiple of the strip): 16x4 threads fill two
// warps of 32 where 8x8 pixels would leave half a warp idle (shaders/README.md).
AOR_CONST uint kSpatialColumnsWorkgroupSize = 16u;

struct SpatialConstants {
  ivec2 size;
  uint pad0;
  uint pad1;
};

AOR_FUNC float spatialGaussian(int dx, int dy) {
  return exp(-float(dx * dx + dy * dy) / (2.0f * kSpatialSigma * kSpatialSigma));
}

#ifndef __cplusplus
// The separable factors spatialGaussian(k, 0) for k = 0..radius, as a constant table for the
// unrolled shader loops.
const float kGaussian1D[kSpatialRadius + 1] = float[](1.0, exp(-1.0 / (2.0 * kSpatialSigma * kSpatialSigma)),
                                                      exp(-4.0 / (2.0 * kSpatialSigma * kSpatialSigma)));
#endif

#include "../common/shared_end.h"
#endif
