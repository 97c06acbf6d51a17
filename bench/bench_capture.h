#pragma once
// Benchmark inputs: the shipped 320x180 capture, resampled (nearest neighbour, so sky stays sky)
// to larger sizes and written once as a capture folder the replayer reads like any other.
#include <filesystem>

#include "capture/capture.h"

namespace aor::bench {

// First `frames` frames of `source` at width x height, cached under `cacheDir`.
Capture resampledCapture(const std::filesystem::path& source, int width, int height, int frames,
                         const std::filesystem::path& cacheDir);

}  // namespace aor::bench
