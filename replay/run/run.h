#pragma once
// A run: a capture replayed under one technique's settings, and what it is judged by. The commands
// (run, sweep, tune) ask for runs here and get typed results back; report/ alone turns them into
// report.json, DOT, HTML and text. What a technique's results need from the tool it declares
// (technique_api/technique.h: its history, the samples its frames average); nothing here names one.
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "capture/capture.h"
#include "metrics/run_analysis.h"
#include "replay_loop/replayer.h"
#include "run/gpu_total.h"

namespace aor {

// Each frame's reference visibility, by capture frame index, and what kind of reference it is.
struct References {
  std::string kind = kRayTracedReference;
  std::map<int, std::vector<float>> frames;
};
// The capture's ray-traced references of the frames in [begin, end) that have one.
References capturedReferences(const Capture& capture, int begin, int end);
// A reference for every frame in [begin, end): the capture's ray-traced ones when each frame has
// one, else the screen-space reference technique replayed with those of `assignments` it declares.
References completeReferences(VulkanContext& vk, const Capture& capture, int begin, int end,
                              const std::vector<std::string>& assignments);

struct RunRequest {
  explicit RunRequest(ReplayOptions options) : replay(std::move(options)) {}
  ReplayOptions replay;
  const References* references = nullptr;  // null: each frame's ray-traced reference, where the capture has one
  bool temporal = true;  // temporal-stability metrics (without references: after a no-history replay)
  bool flip = false;     // FLIP among the error metrics
};

struct RunResults {
  ReplayResult replay;  // device, timings, per-frame records, the last frame's graph
  RunAnalysis analysis;  // error against the references, temporal stability
};

// Per pass name, every timed duration over all frames and repetitions, in first-seen order.
std::vector<std::pair<std::string, std::vector<double>>> samplesByPass(const ReplayResult& result);
// Counted cost: per pass name, its count in each frame (frames in order), in first-seen order.
std::vector<std::pair<std::string, std::vector<double>>> countsByPass(const ReplayResult& result, CostMeasure measure);
// A frame's pass durations as the totals of gpu_total.h take them.
TimedFrame timedFrame(const FrameRecord& frame);
std::vector<TimedFrame> timedFrames(const ReplayResult& result);

// Replays the capture as asked and analyses every frame; `sink` also sees each frame's output
// (images to write, frames to show), after the analysis. Throws as replayCapture does.
RunResults runCapture(VulkanContext& vk, const Capture& capture, const RunRequest& request, const FrameSink& sink = {});

}  // namespace aor
