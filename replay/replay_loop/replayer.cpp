#include "replay_loop/replayer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <future>
#include <limits>
#include <memory>
#include <numeric>

#include <fmt/format.h>
#include <glm/gtc/packing.hpp>

#include "runtime/executor.h"
#include "vk/vk_check.h"
#include "runtime/physical_resources.h"
#include "core/parallel_rows.h"
#include "graph/graph_json.h"
#include "techniques/built_frame.h"

namespace aor {
namespace {

using Clock = std::chrono::steady_clock;
constexpr const char* kKeepsNoHistory = "the technique keeps no history";
double msBetween(Clock::time_point from, Clock::time_point to) {
  return std::chrono::duration<double, std::milli>(to - from).count();
}
double msSince(Clock::time_point t) { return msBetween(t, Clock::now()); }

// Host-visible staging for one frame in flight: G-buffer uploads, the read-back of the result, and
// debug read-backs (made when a frame's graph first asks for them).
struct StagingSlot {
  GpuBuffer depth, normals, depth2, readback;
  std::map<std::string, GpuBuffer> debug;
};

// One slot per frame in flight, used by frames in turn (frame index modulo the slot count). The
// overlapped replay has two: while the GPU runs frame N from one, the decode worker fills the other
// with frame N+1, and the sink of frame N-1 reads its results from the read-backs of that same other
// slot (before frame N+1 is submitted). The isolated replay has one per frame of a preloaded chunk.
// Destroyed in one place.
struct StagingBuffers {
  VulkanContext& vk;
  std::vector<StagingSlot> slots;
  bool normals = false, depth2 = false;
  StagingBuffers(VulkanContext& v, const Capture& capture, bool uploadDepth2, uint32_t outputTexelBytes, int slotCount)
      : vk(v), slots(size_t(slotCount)), normals(capture.hasNormals), depth2(uploadDepth2) {
    VkDeviceSize pixels = VkDeviceSize(capture.width) * VkDeviceSize(capture.height);
    for (auto& slot : slots) {
      slot.depth = createHostBuffer(vk, pixels * sizeof(float), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
      if (normals) slot.normals = createHostBuffer(vk, pixels * 4 * sizeof(uint16_t), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
      if (depth2) slot.depth2 = createHostBuffer(vk, pixels * sizeof(float), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
      slot.readback = createHostBuffer(vk, pixels * outputTexelBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    }
  }
  ~StagingBuffers() {
    for (auto& slot : slots) {
      for (GpuBuffer* b : {&slot.depth, &slot.normals, &slot.depth2, &slot.readback}) destroyBuffer(vk, *b);
      for (auto& [name, b] : slot.debug) destroyBuffer(vk, b);
    }
  }
  StagingSlot& forFrame(int index) { return slots[size_t(index) % slots.size()]; }
  const GpuBuffer* debugTarget(int index, const std::string& name, uint64_t bytes) {
    auto& debug = forFrame(index).debug;
    auto it = debug.find(name);
    if (it != debug.end() && it->second.size != bytes) {
      destroyBuffer(vk, it->second);
      debug.erase(it);
      it = debug.end();
    }
    if (it == debug.end()) it = debug.emplace(name, createHostBuffer(vk, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT)).first;
    return &it->second;
  }
};

// A frame made ready for the GPU on the worker thread: decoded, inputs checked and written into its
// staging slot, so the replay thread only records and submits.
struct DecodedFrame {
  GBuffer gbuffer;
  int64_t invalidDepthPixels = 0, invalidNormalPixels = 0;
  float medianDistance = 0;  // for the camera-jump limit; 0 when there is no history
  double startMs = 0;        // since the set-up started
  double decodeMs = 0, uploadMs = 0;
};

int64_t countInvalidDepth(const GBuffer& g) {
  int64_t invalid = 0;
  for (float d : g.depth) invalid += !(d >= 0.0f && d <= 1.0f);  // NaN fails both comparisons
  return invalid;
}

// Writes RGBA16F (w = 0) into `out`, which holds 4 halves per pixel; returns the pixels with a
// non-finite component. In row bands on all cores: the first frame's is on the critical path.
int64_t packNormals(const GBuffer& g, uint16_t* out) {
  std::vector<int64_t> invalidRows(size_t(g.height), 0);
  size_t width = size_t(g.width);
  forEachRowBand(g.height, [&](int firstRow, int endRow) {
    for (size_t y = size_t(firstRow); y < size_t(endRow); ++y)
      for (size_t i = y * width; i < (y + 1) * width; ++i) {
        bool finite = true;
        for (int c = 0; c < 3; ++c) {
          float v = g.normals[3 * i + size_t(c)];
          finite &= std::isfinite(v);
          out[4 * i + size_t(c)] = glm::packHalf1x16(v);
        }
        out[4 * i + 3] = 0;
        invalidRows[y] += !finite;
      }
  });
  return std::accumulate(invalidRows.begin(), invalidRows.end(), int64_t(0));
}

struct HistoryTracker {
  bool exists = false;
  int width = 0, height = 0;
  Settings settings;
  FrameCamera camera;
  float medianDistance = 0;  // of the frame it holds, for the camera-jump limit

  // Why the previous frame's output must not be blended into this one; empty when it may.
  std::string resetReason(const CaptureFrame& frame, int width, int height, const Settings& current, bool historyWanted,
                          const ReplayOptions& options) const {
    if (!historyWanted) {
      const Technique& t = current.technique();
      HistoryNeeds needs = t.history ? t.history(current) : HistoryNeeds{false, false, kKeepsNoHistory};
      return needs.keeps ? "single-frame replay" : needs.whyNot;
    }
    if (!exists) return "first frame";
    if (frame.cut && !options.keepHistoryOnCut) return "cut";
    if (width != this->width || height != this->height) return "size change";
    if (!(current == settings)) return "settings changed";
    if (frame.cut && options.keepHistoryOnCut) return {};  // test-only: the cut's jump must not reset either
    return cameraJumpReason(camera.view, frame.view, medianDistance, options.cameraJump);
  }
};

// What HistoryTracker::resetReason says of every frame when the technique keeps no history.
std::string noHistoryReason(const Settings& settings) {
  const Technique& t = settings.technique();
  HistoryNeeds needs = t.history ? t.history(settings) : HistoryNeeds{false, false, kKeepsNoHistory};
  return needs.keeps ? "" : needs.whyNot;
}

HistoryStates historyStatesOf(const PhysicalResources& resources) {
  return [&resources](const std::string& base, bool current) { return resources.historyState(base, current); };
}

// Compiles `graph` and records it into the executor's command buffer with its physical resources.
graph::CompiledGraph compileAndRecord(const graph::RenderGraph& graph, PhysicalResources& resources, GraphExecutor& executor) {
  auto compiled = graph.compile();
  executor.record(graph, compiled, resources.prepare(graph, compiled));
  return compiled;
}

// What running one frame's graph gives back: timings of the timed runs, the host time of all runs
// and, when asked, the facts of its compiled graph that the report records.
struct BuiltFrameRuns {
  std::vector<PassTiming> passes;
  double recordMs = 0;  // building, compiling and recording the graph
  double gpuMs = 0;     // from submission to the fence
  std::vector<DebugReadback> debug;
  std::map<std::string, double> values;
  VkFormat outputFormat = VK_FORMAT_UNDEFINED;
  OutputLayout outputLayout;

  std::vector<CulledPassInfo> culled;
  graph::GraphSnapshot graph;
};

// The culled passes with their reasons and the graph as compiled, for the report.
void describeRun(const BuiltFrame& builtFrame, const graph::CompiledGraph& compiled, BuiltFrameRuns& runs) {
  for (const auto& c : compiled.culled) {
    const auto& name = builtFrame.graph.passes()[c.pass].name;
    auto note = builtFrame.notes.find(name);
    runs.culled.push_back({name, note == builtFrame.notes.end() ? c.reason : note->second + "; " + c.reason});
  }
  runs.graph = graph::snapshotOf(builtFrame.graph, compiled);
}

// One run of a frame's graph: timed (a timestamp pair per pass), or with a counter each pass
// submitted alone and counted.
struct RunOfFrame {
  graph::CompiledGraph compiled;
  std::vector<GraphExecutor::PassTime> times;
  std::vector<EventCounts> counts;
};

// `start`: when building the frame's graph began; building, compiling and recording add to
// recordMs, submission to the fence (or the counted submissions) to gpuMs.
RunOfFrame runOnce(const BuiltFrame& builtFrame, PhysicalResources& resources, GraphExecutor& executor,
                   CallgrindCounter* counter, Clock::time_point start, BuiltFrameRuns& runs) {
  RunOfFrame run;
  run.compiled = counter ? builtFrame.graph.compile() : compileAndRecord(builtFrame.graph, resources, executor);
  auto recorded = Clock::now();
  runs.recordMs += msBetween(start, recorded);
  if (counter)
    run.counts = executor.countPasses(builtFrame.graph, run.compiled, resources.prepare(builtFrame.graph, run.compiled), *counter);
  else
    run.times = executor.submitAndWait();
  runs.gpuMs += msSince(recorded);
  resources.keepFinalStates(builtFrame.graph, run.compiled);
  return run;
}

void keepMeasures(const BuiltFrame& builtFrame, RunOfFrame& run, BuiltFrameRuns& runs) {
  if (runs.passes.empty())
    for (const auto& p : run.compiled.passes) runs.passes.push_back({builtFrame.graph.passes()[p.pass].name, 0, {}, {}});
  for (size_t i = 0; i < run.times.size(); ++i) {
    runs.passes[i].startMs = run.times[i].startMs;
    runs.passes[i].durationsMs.push_back(run.times[i].durationMs);
  }
  for (size_t i = 0; i < run.counts.size(); ++i) runs.passes[i].counts = std::move(run.counts[i]);
  runs.debug = builtFrame.debug;
  runs.values = builtFrame.values;
  runs.outputFormat = builtFrame.outputFormat;
  runs.outputLayout = builtFrame.outputLayout;
}

// Executes the frame's graph `warmup + repeat` times (only the last `repeat` are timed; with a
// counter, the run after the warm-up is counted instead). The graph is rebuilt per run: each run
// starts from the image states the previous one left.
BuiltFrameRuns runBuiltFrame(const FrameBuilder::Setup& setup, PipelineCache& pipelines, PhysicalResources& resources,
                             GraphExecutor& executor, const FrameBuffers& buffers, int warmup, int repeat, bool describeGraph,
                             CallgrindCounter* counter) {
  BuiltFrameRuns runs;
  for (int run = 0; run < warmup + repeat; ++run) {
    auto start = Clock::now();
    auto builtFrame = buildFrame(pipelines, setup, buffers);
    RunOfFrame once = runOnce(builtFrame, resources, executor, run >= warmup ? counter : nullptr, start, runs);
    if (run < warmup) continue;
    keepMeasures(builtFrame, once, runs);
    if (describeGraph && run + 1 == warmup + repeat) describeRun(builtFrame, once.compiled, runs);
  }
  return runs;
}

// Test-only (ReplayOptions::testPoisonHistoryAt): overwrites the "ao_history" the next frame reads
// with NaN, through the graph so the barriers stay derived.
void poisonHistory(const FrameBuilder::Setup& setup, graph::ImageDesc desc, PhysicalResources& resources,
                   GraphExecutor& executor) {
  auto poison = buildHistoryPoisonGraph(setup, "ao_history", desc, std::numeric_limits<float>::quiet_NaN());
  auto compiled = compileAndRecord(poison, resources, executor);
  executor.submitAndWait();
  resources.keepFinalStates(poison, compiled);
}

// Set-up, outside the replay's wall time as device creation is: the first frame's graph is recorded
// once and not submitted, which creates the pipelines of its live passes and its images, and the
// graph of a frame with history is built and recorded too, which creates the pipelines every later
// frame uses. Pipeline creation (about 17 ms on lavapipe) then never lands in a frame's time;
// lavapipe's compile to machine code happens at a shader's first dispatch, so there that part still
// lands in the first frame (docs/outputs.md, setup_ms).
void prepareFirstFrame(FrameBuilder::Setup setup, PipelineCache& pipelines, PhysicalResources& resources,
                       GraphExecutor& executor, const FrameBuffers& buffers) {
  compileAndRecord(buildFrame(pipelines, setup, buffers).graph, resources, executor);
  if (!setup.historyWanted) return;
  setup.historyValid = true;
  setup.previousCamera = setup.camera;
  compileAndRecord(buildFrame(pipelines, setup, buffers).graph, resources, executor);
}


void checkRange(const Capture& capture, int begin, int end, int total) {
  if (begin < 0 || begin >= end || end > total)
    throw InputError((capture.folder / "capture.json").string(), std::nullopt, "--frames",
                     fmt::format("range {}:{} is not inside the capture's {} frames (half-open A:B with 0 <= A < B <= {})",
                                 begin, end, total, total));
}

void checkTechnique(const VulkanContext& vk, const Capture& capture, const ReplayOptions& options) {
  const Settings& settings = options.settings;
  const Technique& t = settings.technique();
  std::string file = (capture.folder / "capture.json").string();
  if (t.inputs.normals == InputUse::Required && !capture.hasNormals)
    throw InputError(file, std::nullopt, "normals", fmt::format("technique {} needs normals; the capture has none", t.name));
  if (t.inputs.depth2 == InputUse::Required && !capture.hasDepth2)
    throw InputError(file, std::nullopt, "depth2", fmt::format("technique {} needs a second depth layer; the capture has none", t.name));
  for (const auto& view : options.debugViews)
    if (!t.debugView(view)) {
      std::vector<std::string> names;
      for (const auto& v : t.debugViews) names.push_back(v.name);
      throw InputError("", std::nullopt, "--debug",
                       fmt::format("technique {} has no debug view '{}' (views: {})", t.name, view,
                                   names.empty() ? "none" : fmt::format("{}", fmt::join(names, ", "))));
    }
  if (t.checkCapture) t.checkCapture(settings, capture);
  if (t.checkDeviceLimits) t.checkDeviceLimits(vk.info);
  if (t.missingDeviceExtensions) {
    auto missing = t.missingDeviceExtensions(settings, vk.info);
    if (!missing.empty())
      throw NoDeviceError(fmt::format("technique {} with these settings needs {}, which device '{}' lacks", t.name,
                                      fmt::join(missing, ", "), vk.info.name));
  }
}

}  // namespace

HostOverhead hostOverhead(const ReplayResult& result) {
  double gpu = 0;
  for (const auto& f : result.frames) gpu += f.gpuWallMs;
  HostOverhead h;
  h.ms = std::max(0.0, result.wallMs - gpu);
  h.fractionOfWall = result.wallMs > 0 ? h.ms / result.wallMs : 0.0;
  return h;
}

TimingMode resolveTimingMode(TimingMode requested, const DeviceInfo& device) {
  if (requested != TimingMode::Auto) return requested;
  return device.isCpu ? TimingMode::Isolated : TimingMode::Overlapped;
}

const char* timingModeName(TimingMode mode) {
  switch (mode) {
    case TimingMode::Auto: return "auto";
    case TimingMode::Isolated: return "isolated";
    case TimingMode::Overlapped: return "overlapped";
  }
  return "?";
}

namespace {

// What the sink of one frame reports back: when it ran, how long the conversion and the sink took,
// and the debug counters it read.
struct SinkTimes {
  double startMs = 0, readbackMs = 0, writeMs = 0;
  std::vector<DebugCounters> counters;
};

// One replay of a frame range: the set-up, then the frames in one of two orders (TimingMode). The
// pieces every order shares are decode (into the frame's staging slot), runFrame (the timed GPU work
// and the history decision) and sinkFrame (read-back to floats and the caller's sink).
class Replay {
 public:
  Replay(VulkanContext& vk, const Capture& capture, const ReplayOptions& options, const FrameSink& sink, int begin, int end)
      : vk_(vk), capture_(capture), options_(options), sink_(sink), begin_(begin), end_(end),
        settings_(options.settings), historyWanted_(historyNeedsOf(settings_, end - begin).keeps),
        pipelines_(vk), resources_(vk), executor_(vk) {
    if (options.cost != CostMeasure::Time) counter_ = std::make_unique<CallgrindCounter>(options.costDumps);
  }

  ReplayResult run() {
    result_.device = vk_.info;
    result_.settings = settings_;
    result_.timingMode = resolveTimingMode(options_.timingMode, vk_.info);
    result_.noHistoryReason = noHistoryReason(settings_);
    result_.cost = options_.cost;
    setupStart_ = Clock::now();  // the origin of every start time in the result
    const Technique& technique = settings_.technique();
    if (technique.prepare) state_ = technique.prepare(ReplaySetup{capture_, settings_, &vk_});
    if (state_) result_.techniqueState = state_->reportValues();
    layout_ = {capture_.hasNormals, capture_.hasDepth2 && technique.inputs.depth2 != InputUse::Unused};
    BuiltFrame dry = buildFrame(pipelines_, setupFor(begin_, {}, false), {});  // the output's format, never run
    checkDebugViewsWritten(dry);
    outputTexelBytes_ = graph::bytesPerPixel(dry.outputFormat);
    outputDesc_ = dry.graph.resources()[dry.output].desc;
    int slots = 2;
    if (result_.timingMode == TimingMode::Isolated) {
      chunkFrames_ = framesPerChunk(dry);
      slots = std::min(chunkFrames_, end_ - begin_);
      result_.chunkFrames = std::min(chunkFrames_, end_ - begin_);
    }
    staging_ = std::make_unique<StagingBuffers>(vk_, capture_, layout_.depth2, outputTexelBytes_, std::max(slots, 1));
    if (result_.timingMode == TimingMode::Isolated)
      runIsolated();
    else
      runOverlapped();
    return std::move(result_);
  }

 private:
  // A view the technique declares may still not exist with these settings (cacao's importance map
  // below `highest`, a MIP level a small frame does not have): say so instead of writing nothing.
  void checkDebugViewsWritten(const BuiltFrame& dry) const {
    for (const auto& view : options_.debugViews) {
      bool written = std::any_of(dry.debug.begin(), dry.debug.end(), [&](const DebugReadback& d) { return d.name == view; });
      if (!written)
        throw InputError("", std::nullopt, "--debug",
                         fmt::format("technique {} writes no debug view '{}' with these settings ({})",
                                     settings_.technique().name, view, settings_.toJson().dump()));
    }
  }

  FrameCamera frameCamera(int index) const {
    const auto& frame = capture_.frames[size_t(index)];
    return FrameCamera{frame.view, frame.projection, capture_.width, capture_.height, uint32_t(index)};
  }

  FrameBuilder::Setup setupFor(int index, const FrameCamera& previous, bool valid) {
    FrameBuilder::Setup s;
    s.settings = &settings_;
    s.camera = frameCamera(index);
    s.previousCamera = previous;
    s.capture = layout_;
    s.historyWanted = historyWanted_;
    s.historyValid = valid;
    s.debugViews = options_.debugViews;
    s.state = state_.get();
    s.historyStates = historyStatesOf(resources_);
    if (staging_)
      s.debugTarget = [staging = staging_.get(), index](const std::string& name, uint64_t bytes) {
        return staging->debugTarget(index, name, bytes);
      };
    return s;
  }

  FrameBuffers frameBuffers(int index) {
    StagingSlot& slot = staging_->forFrame(index);
    return FrameBuffers{{&slot.depth, staging_->normals ? &slot.normals : nullptr, staging_->depth2 ? &slot.depth2 : nullptr},
                        &slot.readback};
  }

  // How many frames a preloaded chunk holds: what --preload-budget allows for their staging memory,
  // their decoded G-buffers and their debug read-backs, at most kMaxChunkFrames (each slot is a few
  // host allocations). A budget too small for one frame is bad input.
  static constexpr int kMaxChunkFrames = 64;
  int framesPerChunk(const BuiltFrame& dry) const {
    uint64_t pixels = uint64_t(capture_.width) * uint64_t(capture_.height);
    uint64_t staging = pixels * (sizeof(float) + (capture_.hasNormals ? 4 * sizeof(uint16_t) : 0) +
                                 (layout_.depth2 ? sizeof(float) : 0) + outputTexelBytes_);
    uint64_t decoded = pixels * sizeof(float) * (1 + (capture_.hasNormals ? 3 : 0) + (capture_.hasDepth2 ? 1 : 0));
    uint64_t debug = 0;
    for (const auto& d : dry.debug)
      debug += d.format == VK_FORMAT_UNDEFINED ? dry.graph.resources()[d.resource].buffer.bytes
                                               : graph::imageBytes({d.width, d.height, d.format});
    uint64_t perFrame = staging + decoded + debug;
    uint64_t fit = options_.preloadBudgetBytes / std::max<uint64_t>(perFrame, 1);
    if (fit == 0)
      throw InputError((capture_.folder / "capture.json").string(), std::nullopt, "--preload-budget",
                       fmt::format("one frame of this capture needs {:.1f} MiB preloaded; the budget is {:.1f} MiB",
                                   double(perFrame) / (1 << 20), double(options_.preloadBudgetBytes) / (1 << 20)));
    return int(std::min<uint64_t>(fit, kMaxChunkFrames));
  }

  DecodedFrame decode(int index) {
    auto t = Clock::now();
    DecodedFrame d;
    d.startMs = msBetween(setupStart_, t);
    d.gbuffer = loadGBuffer(capture_, index);
    d.invalidDepthPixels = countInvalidDepth(d.gbuffer);
    if (historyWanted_) d.medianDistance = medianViewDistance(d.gbuffer.depth, capture_.frames[size_t(index)].projection);
    d.decodeMs = msSince(t);
    t = Clock::now();
    StagingSlot& slot = staging_->forFrame(index);
    std::memcpy(slot.depth.mapped, d.gbuffer.depth.data(), d.gbuffer.depth.size() * sizeof(float));
    if (staging_->normals) d.invalidNormalPixels = packNormals(d.gbuffer, static_cast<uint16_t*>(slot.normals.mapped));
    if (staging_->depth2) std::memcpy(slot.depth2.mapped, d.gbuffer.depth2.data(), d.gbuffer.depth2.size() * sizeof(float));
    d.uploadMs = msSince(t);
    return d;
  }

  void prepare() {
    prepareFirstFrame(setupFor(begin_, {}, false), pipelines_, resources_, executor_, frameBuffers(begin_));
    result_.setupMs = msSince(setupStart_);
  }

  // The frame's timed GPU work: history decision, `warmup + repeat` runs of its graph, and the
  // history bookkeeping for the next frame. Fills `record` from the decode and the runs.
  BuiltFrameRuns runFrame(int index, const DecodedFrame& decoded, FrameRecord& record) {
    record.index = index;
    record.workerStartMs = decoded.startMs;
    record.decodeMs = decoded.decodeMs;
    record.uploadMs = decoded.uploadMs;
    record.invalidDepthPixels = decoded.invalidDepthPixels;
    record.invalidNormalPixels = decoded.invalidNormalPixels;
    const auto& frame = capture_.frames[size_t(index)];
    FrameCamera camera = frameCamera(index);
    record.resetReason = history_.resetReason(frame, capture_.width, capture_.height, settings_, historyWanted_, options_);
    record.historyValid = record.resetReason.empty();
    if (history_.exists && (history_.width != capture_.width || history_.height != capture_.height)) resources_.dropHistory();

    auto setup = setupFor(index, history_.camera, record.historyValid);
    if (index == options_.testPoisonHistoryAt && record.historyValid) poisonHistory(setup, outputDesc_, resources_, executor_);
    bool lastFrame = index + 1 == end_;
    auto runs = runBuiltFrame(setup, pipelines_, resources_, executor_, frameBuffers(index), options_.warmup,
                              options_.repeat, lastFrame, counter_.get());
    record.passes = std::move(runs.passes);
    record.techniqueValues = runs.values;
    record.recordMs = runs.recordMs;
    record.gpuWallMs = runs.gpuMs;
    if (lastFrame) {
      result_.culled = std::move(runs.culled);
      result_.graph = std::move(runs.graph);
    }
    if (historyWanted_) resources_.swapHistory();
    history_ = {true, capture_.width, capture_.height, settings_, camera, decoded.medianDistance};
    return runs;
  }

  bool wantsSink(const BuiltFrameRuns& runs) const { return sink_ || !runs.debug.empty(); }

  // Read-back to floats (output and debug views) from the frame's slot, then the caller's sink.
  SinkTimes sinkFrame(int index, const DecodedFrame& frame, bool valid, const std::string& reason, const BuiltFrameRuns& runs) {
    auto start = Clock::now();
    SinkTimes times;
    times.startMs = msBetween(setupStart_, start);
    const StagingSlot& slot = staging_->forFrame(index);
    size_t pixels = size_t(capture_.width) * size_t(capture_.height);
    auto decodedOutput = decodeOutput(slot.readback.mapped, runs.outputFormat, runs.outputLayout, pixels);
    FrameOutput output;
    output.index = index;
    output.width = capture_.width;
    output.height = capture_.height;
    output.visibility = std::move(decodedOutput.visibility);
    output.bent = std::move(decodedOutput.bent);
    for (const auto& d : runs.debug) {
      if (!d.target) continue;
      if (d.format != VK_FORMAT_UNDEFINED) {
        output.debugImages.push_back({d.name, int(d.width), int(d.height), decodableChannels(d.format),
                                      decodeTexels(d.target->mapped, d.format, size_t(d.width) * d.height)});
      } else {
        const auto* words = static_cast<const uint32_t*>(d.target->mapped);
        times.counters.push_back({d.name, std::vector<uint32_t>(words, words + d.target->size / sizeof(uint32_t))});
      }
    }
    times.readbackMs = msSince(start);
    auto written = Clock::now();
    output.gbuffer = &frame.gbuffer;
    output.historyValid = valid;
    output.resetReason = reason;
    if (sink_) sink_(output);
    times.writeMs = msSince(written);
    return times;
  }

  static void keepSinkTimes(FrameRecord& record, SinkTimes times) {
    record.sinkStartMs = times.startMs;
    record.readbackMs = times.readbackMs;
    record.writeMs = times.writeMs;
    record.debugCounters = std::move(times.counters);
  }

  void progress(int index) const {
    if (options_.progress) options_.progress(index - begin_ + 1, end_ - begin_);
  }

  // The frames pipelined: frame N+1 decodes on a worker and frame N-1's sink runs on another while
  // the GPU runs frame N. The most frames per second, but the workers share the CPU (a CPU device's
  // too) with the frame being timed.
  void runOverlapped() {
    auto next = std::async(std::launch::async, [this] { return decode(begin_); });  // overlaps the set-up
    prepare();
    auto replayStart = Clock::now();
    std::future<SinkTimes> pendingSink;
    size_t pendingRecord = 0;
    auto finishPendingSink = [&] {
      if (pendingSink.valid()) keepSinkTimes(result_.frames[pendingRecord], pendingSink.get());
    };
    for (int index = begin_; index < end_; ++index) {
      FrameRecord record;
      record.hostStartMs = msSince(setupStart_);
      DecodedFrame decoded = next.get();
      record.waitMs = msSince(setupStart_) - record.hostStartMs;
      if (index + 1 < end_) next = std::async(std::launch::async, [this, index] { return decode(index + 1); });
      auto runs = runFrame(index, decoded, record);
      finishPendingSink();  // the previous frame's sink: its slot is the next frame's
      if (wantsSink(runs)) {
        pendingRecord = result_.frames.size();  // the record pushed below
        pendingSink = std::async(std::launch::async, [this, index, frame = std::move(decoded), valid = record.historyValid,
                                                      reason = record.resetReason, runs = std::move(runs)] {
          return sinkFrame(index, frame, valid, reason, runs);
        });
      }
      result_.frames.push_back(std::move(record));
      progress(index);
    }
    finishPendingSink();
    result_.wallMs = msSince(replayStart);
  }

  // No thread of the tool runs while a frame's GPU work is timed: each chunk of frames is decoded and
  // written into its staging slots first, then its frames run one after the other, then their
  // read-backs are converted and sunk, in frame order. The `upload` copy stays each frame's timed pass.
  void runIsolated() {
    prepare();
    auto replayStart = Clock::now();
    for (int chunkBegin = begin_; chunkBegin < end_; chunkBegin += chunkFrames_) {
      int chunkEnd = std::min(end_, chunkBegin + chunkFrames_);
      std::vector<DecodedFrame> decoded;
      for (int index = chunkBegin; index < chunkEnd; ++index) decoded.push_back(decode(index));
      std::vector<BuiltFrameRuns> runs;
      size_t first = result_.frames.size();
      for (int index = chunkBegin; index < chunkEnd; ++index) {
        FrameRecord record;
        record.hostStartMs = msSince(setupStart_);
        runs.push_back(runFrame(index, decoded[size_t(index - chunkBegin)], record));
        result_.frames.push_back(std::move(record));
      }
      for (int index = chunkBegin; index < chunkEnd; ++index) {
        size_t k = size_t(index - chunkBegin);
        FrameRecord& record = result_.frames[first + k];
        if (wantsSink(runs[k])) keepSinkTimes(record, sinkFrame(index, decoded[k], record.historyValid, record.resetReason, runs[k]));
        progress(index);
      }
    }
    result_.wallMs = msSince(replayStart);
  }

  VulkanContext& vk_;
  const Capture& capture_;
  const ReplayOptions& options_;
  const FrameSink& sink_;
  int begin_, end_;
  const Settings& settings_;
  bool historyWanted_;
  std::unique_ptr<TechniqueState> state_;
  CaptureLayout layout_;
  uint32_t outputTexelBytes_ = 0;
  graph::ImageDesc outputDesc_;
  int chunkFrames_ = 0;
  PipelineCache pipelines_;
  PhysicalResources resources_;
  GraphExecutor executor_;
  std::unique_ptr<CallgrindCounter> counter_;  // counted cost only
  std::unique_ptr<StagingBuffers> staging_;
  HistoryTracker history_;
  Clock::time_point setupStart_;
  ReplayResult result_;
};

}  // namespace

ReplayResult replayCapture(VulkanContext& vk, const Capture& capture, const ReplayOptions& options, const FrameSink& sink) {
  int total = int(capture.frames.size());
  int begin = options.frameBegin, end = options.frameEnd < 0 ? total : options.frameEnd;
  checkRange(capture, begin, end, total);
  checkTechnique(vk, capture, options);
  return Replay(vk, capture, options, sink, begin, end).run();
}

}  // namespace aor
