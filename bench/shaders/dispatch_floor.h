#ifndef AOR_DISPATCH_FLOOR_H
#define AOR_DISPATCH_FLOOR_H
// dispatch_floor.comp (bench/dispatch_floor.cpp): what one compute dispatch costs before it does
// any work, and what its one image store costs, per device.
#include "../../shaders/common/shared_begin.h"

AOR_CONST int kFloorSpecMode = 0;
AOR_CONST int kFloorSpecWorkgroupSize = 1;  // square workgroups, pixels a side
AOR_CONST int kFloorModeNothing = 0;    // bounds check only: the cost of running the invocations
AOR_CONST int kFloorModeStore = 1;      // one store of a constant into the target's format
AOR_CONST int kFloorModeCopy = 2;       // one RGBA16F load, one store
AOR_CONST uint kFloorWorkgroupSize = 8u;  // default: the denoisers' size

struct FloorConstants {
  ivec2 size;
};

#include "../../shaders/common/shared_end.h"
#endif
