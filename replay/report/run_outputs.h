#pragma once
// What `aoreplay run` writes: ao/NNNN.exr + ao/NNNN.png per frame, report.json, trace.json.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "capture/capture.h"
#include "replay_loop/replayer.h"
#include "run/run.h"

namespace aor {

// ao/NNNN.exr and .png; debug/VIEW/NNNN.exr and .png for a debug view read back.
void writeFrameImages(const std::filesystem::path& outDir, const FrameOutput& frame);
void writeDebugImage(const std::filesystem::path& outDir, int frameIndex, const DebugImage& view);
nlohmann::json buildReport(const Capture& capture, const ReplayOptions& options, const ReplayResult& result);
// The same with the run's metrics: frames[i].metrics and metrics.
nlohmann::json buildReport(const Capture& capture, const ReplayOptions& options, const RunResults& run);
// Chrome trace-event format: one track for GPU passes, one for the host's per-frame phases.
nlohmann::json buildTrace(const ReplayResult& result);
// Writes `text` to `path`; throws std::runtime_error "cannot write PATH" on failure.
void writeText(const std::filesystem::path& path, const std::string& text);
// json.dump(2) and a newline, through writeText.
void writeJson(const std::filesystem::path& path, const nlohmann::json& json);
// Per-pass table (min / median / max GPU ms over all timed runs) for the terminal, and the total's
// row: the same over the per-repetition sums of the compute passes (report/gpu_total.h).
std::string passTable(const ReplayResult& result);
// Counted cost's "cost" block: the measure and everything its counts depend on (device, driver,
// CPU as the counted process sees it, valgrind, for cycles the cache geometry and formula) and
// "key", all of it in one string: two runs' counts compare exactly only when their keys are equal.
nlohmann::json costDependencies(CostMeasure measure, const DeviceInfo& device);
// Counted cost's table: per pass its count over the frames and the largest of a frame.
std::string countedPassTable(const ReplayResult& result, CostMeasure measure);

}  // namespace aor
