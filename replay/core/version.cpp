#include "core/version.h"

#ifndef AOREPLAY_VERSION
#define AOREPLAY_VERSION "unknown"
#endif

namespace aor {

const char* aoreplayVersion() { return AOREPLAY_VERSION; }

}  // namespace aor
