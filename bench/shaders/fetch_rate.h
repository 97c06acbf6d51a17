#ifndef AOR_FETCH_RATE_H
#define AOR_FETCH_RATE_H
// fetch_rate.comp (bench/device_rates.cpp): texelFetch per millisecond of a device.
#include "../../shaders/common/shared_begin.h"

AOR_CONST int kFetchRateTaps = 64;
AOR_CONST int kFetchRatePad = 8;  // source texels beyond the grid, right and below (the 8x8 neighbourhood)

struct FetchRateConstants {
  ivec2 size;
};

#include "../../shaders/common/shared_end.h"
#endif
