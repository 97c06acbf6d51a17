#pragma once
// The replay loop: decode a frame's G-buffer (one frame ahead, on a worker thread), upload it, run
// the frame's compiled render graph `warmup + repeat` times with timestamps, read the result back,
// and decide history validity for the next frame. Outputs go to a FrameSink. Which passes run is
// the technique's (technique_api/technique.h); this loop is the same for every technique.
#include <filesystem>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "capture/capture.h"
#include "cost/callgrind_counter.h"
#include "graph/render_graph.h"
#include "replay_loop/camera_jump.h"
#include "replay_loop/readback.h"
#include "technique_api/settings.h"
#include "vk/context.h"

namespace aor {

// How the frames of a replay are ordered against the tool's own work (docs/guide.md, "Timing").
enum class TimingMode {
  Auto,        // Isolated on a CPU device (lavapipe, llvmpipe, SwiftShader), Overlapped on a GPU
  Isolated,    // each chunk of frames decoded before its GPU work and sunk after: nothing of the
               // tool's runs while a frame is timed
  Overlapped,  // decode of the next frame and sink of the last on workers, during the GPU work
};
TimingMode resolveTimingMode(TimingMode requested, const DeviceInfo& device);
const char* timingModeName(TimingMode mode);  // "isolated", "overlapped"
inline constexpr uint64_t kDefaultPreloadBudgetBytes = uint64_t(1024) << 20;

struct ReplayOptions {
  explicit ReplayOptions(Settings s) : settings(std::move(s)) {}
  Settings settings;
  int frameBegin = 0;      // half-open [frameBegin, frameEnd)
  int frameEnd = -1;       // -1: to the end
  int repeat = 1;          // timed executions per frame
  int warmup = 0;          // untimed executions per frame before the timed ones
  std::set<std::string> debugViews;  // --debug views to read back (names the technique declares)
  TimingMode timingMode = TimingMode::Auto;
  uint64_t preloadBudgetBytes = kDefaultPreloadBudgetBytes;  // Isolated: what a chunk of frames may hold
  bool keepHistoryOnCut = false;  // test-only: breaks history invalidation on purpose
  int testPoisonHistoryAt = -1;   // test-only: before this frame (if its history is valid) its "ao_history" is NaN
  CameraJumpLimits cameraJump;    // history is also reset when the camera turns or moves further
  CostMeasure cost = CostMeasure::Time;  // counted: one run a frame after the warm-up, under callgrind
  std::filesystem::path costDumps;       // counted: the --callgrind-out-file valgrind was given
  std::function<void(int done, int total)> progress;
};

struct PassTiming {
  std::string name;
  double startMs = 0;                // start within the frame's GPU work (last repetition)
  std::vector<double> durationsMs;   // one per timed repetition; none under counted cost
  EventCounts counts;                // counted cost: callgrind's events of the pass's one counted run
};

struct FrameRecord {
  int index = 0;                     // frame index in the capture
  bool historyValid = false;
  std::string resetReason;           // empty when valid
  std::vector<PassTiming> passes;    // live passes in execution order
  // Host-side wall time of this frame, milliseconds. Decode and upload (writing the staging memory)
  // run ahead on the decode worker; readback (converting the mapped read-back to floats) and write
  // (the sink: images, analysis) run behind on the sink worker. Only wait, record (building,
  // compiling and recording the graph) and gpu (submission to fence) are on the replay thread's
  // critical path; record and gpu add up all runs of the frame (warm-up included).
  double decodeMs = 0, uploadMs = 0, waitMs = 0, recordMs = 0, gpuWallMs = 0, readbackMs = 0, writeMs = 0;
  double hostStartMs = 0;            // since the set-up started: when the replay thread took the frame
  double workerStartMs = 0;          // when the decode worker started it
  double sinkStartMs = 0;            // when the sink worker started it
  int64_t invalidDepthPixels = 0;    // NaN, Inf or outside [0,1]
  int64_t invalidNormalPixels = 0;   // NaN or Inf in a normal component (uploaded as is, ignored by GTAO)
  std::vector<DebugCounters> debugCounters;  // debug buffers the run asked for (report.json frames[i].debug)
  std::map<std::string, double> techniqueValues;  // FrameBuilder::reportValue (report.json frames[i].technique)
};

struct FrameOutput {
  int index = 0;
  int width = 0, height = 0;
  std::vector<float> visibility;  // width*height
  std::vector<float> bent;        // width*height*3 view-space bent normals; empty without them
  std::vector<DebugImage> debugImages;  // the debug views the run asked for
  const GBuffer* gbuffer = nullptr;  // the frame's inputs, valid during the sink call
  bool historyValid = false;
  std::string resetReason;
};

struct CulledPassInfo {
  std::string name;
  std::string reason;  // the graph's reason, plus the setting or input behind it
};

struct ReplayResult {
  DeviceInfo device;
  Settings settings;
  TimingMode timingMode = TimingMode::Overlapped;  // the mode the replay ran in (never Auto)
  CostMeasure cost = CostMeasure::Time;            // passes[].counts hold the measure's events unless Time
  int chunkFrames = 0;                             // Isolated: frames preloaded per chunk
  std::vector<FrameRecord> frames;
  // The reset reason every frame gets when the technique keeps no history under these settings
  // (HistoryNeeds::whyNot, "temporal=0"); empty when it keeps history.
  std::string noHistoryReason;
  std::vector<CulledPassInfo> culled;       // of the last frame's graph
  graph::GraphSnapshot graph;               // the last frame's graph, as compiled
  std::vector<std::pair<std::string, double>> techniqueState;  // TechniqueState::reportValues
  double setupMs = 0;  // staging memory, pipelines and the first frame's images; the first decode overlaps it
  double wallMs = 0;   // from the end of the set-up to the end of the last frame's sink
};

// Wall time not spent in GPU work (submission to fence): waiting for a decode, recording, and the
// last frame's sink. What the host adds to a replay's wall time.
struct HostOverhead {
  double ms = 0;
  double fractionOfWall = 0;
};
HostOverhead hostOverhead(const ReplayResult& result);

// Returns what to record for the frame (its write time is measured by the replayer).
using FrameSink = std::function<void(const FrameOutput&)>;

// Throws InputError for settings the capture cannot take and for --frames outside it, and
// NoDeviceError when the device lacks what the settings need; both before any GPU work.
ReplayResult replayCapture(VulkanContext& vk, const Capture& capture, const ReplayOptions& options, const FrameSink& sink);

}  // namespace aor
