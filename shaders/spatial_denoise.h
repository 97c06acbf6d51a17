#ifndef AOR_SPATIAL_DENOISE_H
#define AOR_SPATIAL_DENOISE_H
// Pass 2 of seed 000: 5x5 bilateral blur, Gaussian sigma 1.5, with edge weights multiplied along a
// grid path from the centre (horizontal leg first, then vertical) so no tap tunnels through an edge.
#include "common.h"
#include "shared_begin.h"

AOR_CONST int kSpatialSpecBent = 0;
AOR_CONST int kSpatialRadius = 2;          // 5x5
AOR_CONST float kSpatialSigma = 1.5f;

struct SpatialConstants {
  ivec2 size;
  uint pad0;
  uint pad1;
};

AOR_FUNC float spatialGaussian(int dx, int dy) {
  return exp(-float(dx * dx + dy * dy) / (2.0f * kSpatialSigma * kSpatialSigma));
}

#include "shared_end.h"
#endif
