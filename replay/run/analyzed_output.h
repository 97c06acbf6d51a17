#pragma once
// A replayed frame as the metrics see it (metrics/analyzed_frame.h): its output beside the capture
// frame it came from. One place, so run, sweep and tune measure the same thing.
#include <vector>

#include "capture/capture.h"
#include "metrics/analyzed_frame.h"
#include "replay_loop/replayer.h"

namespace aor {

// Valid while `frame` and `reference` are (during the sink call). `reference` may be null.
AnalyzedFrame analyzedFrame(const Capture& capture, const FrameOutput& frame, const std::vector<float>* reference);

}  // namespace aor
