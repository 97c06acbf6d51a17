#ifndef AOR_COPY_RATE_H
#define AOR_COPY_RATE_H
// copy_rate.comp (bench/device_rates.cpp): bytes a compute shader moves per millisecond.
#include "../../shaders/common/shared_begin.h"

AOR_CONST uint kCopyRateWorkgroupSize = 256u;
AOR_CONST uint kCopyRateMaxGroups = 16384u;  // a grid-stride loop covers the rest

struct CopyRateConstants {
  uint vec4s;  // 16-byte elements to copy
};

#include "../../shaders/common/shared_end.h"
#endif
