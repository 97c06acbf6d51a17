#include "pipeline/replayer.h"

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

#include "graph/executor.h"
#include "vk/vk_check.h"
#include "graph/physical_resources.h"
#include "metrics/parallel_rows.h"
#include "report/graph_json.h"
#include "techniques/frame_graph.h"

namespace aor {
namespace {

using Clock = std::chrono::steady_clock;
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

// Two slots, used by alternate frames: while the GPU runs frame N from one slot, the decode worker
// fills the other with frame N+1, and the sink of frame N-1 reads its results from the read-backs of
// that same other slot (before frame N+1 is submitted). Destroyed in one place.
struct StagingBuffers {
  VulkanContext& vk;
  StagingSlot slots[2];
  bool normals = false, depth2 = false;
  StagingBuffers(VulkanContext& v, const Capture& capture, bool uploadDepth2, uint32_t outputTexelBytes)
      : vk(v), normals(capture.hasNormals), depth2(uploadDepth2) {
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
  StagingSlot& forFrame(int index) { return slots[index % 2]; }
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
      HistoryNeeds needs = t.history ? t.history(current) : HistoryNeeds{false, false, "the technique keeps no history"};
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
struct FrameGraphRuns {
  std::vector<PassTiming> passes;
  double recordMs = 0;  // building, compiling and recording the graph
  double gpuMs = 0;     // from submission to the fence
  std::vector<DebugReadback> debug;
  VkFormat outputFormat = VK_FORMAT_UNDEFINED;
  OutputLayout outputLayout;

  std::vector<CulledPassInfo> culled;
  std::string description;
  uint64_t peakBytes = 0, unaliasedBytes = 0;
  nlohmann::json resources;
};

// Executes the frame's graph `warmup + repeat` times (only the last `repeat` are timed). The graph
// is rebuilt per run: each run starts from the image states the previous one left.
FrameGraphRuns runFrameGraph(const FrameBuilder::Setup& setup, PipelineCache& pipelines, PhysicalResources& resources,
                             GraphExecutor& executor, const FrameBuffers& buffers, int warmup, int repeat, bool describeGraph) {
  FrameGraphRuns runs;
  for (int run = 0; run < warmup + repeat; ++run) {
    auto start = Clock::now();
    auto frameGraph = buildFrameGraph(pipelines, setup, buffers);
    auto compiled = compileAndRecord(frameGraph.graph, resources, executor);
    auto recorded = Clock::now();
    auto times = executor.submitAndWait();
    runs.recordMs += msBetween(start, recorded);
    runs.gpuMs += msSince(recorded);
    resources.keepFinalStates(frameGraph.graph, compiled);
    if (run < warmup) continue;
    if (runs.passes.empty())
      for (const auto& p : compiled.passes) runs.passes.push_back({frameGraph.graph.passes()[p.pass].name, 0, {}});
    for (size_t i = 0; i < times.size(); ++i) {
      runs.passes[i].startMs = times[i].startMs;
      runs.passes[i].durationsMs.push_back(times[i].durationMs);
    }
    runs.debug = frameGraph.debug;
    runs.outputFormat = frameGraph.outputFormat;
    runs.outputLayout = frameGraph.outputLayout;
    if (!describeGraph || run + 1 < warmup + repeat) continue;
    for (const auto& c : compiled.culled) {
      const auto& name = frameGraph.graph.passes()[c.pass].name;
      auto note = frameGraph.notes.find(name);
      runs.culled.push_back({name, note == frameGraph.notes.end() ? c.reason : note->second + "; " + c.reason});
    }
    runs.description = graph::describe(frameGraph.graph, compiled);
    runs.peakBytes = compiled.peakBytes();
    runs.unaliasedBytes = compiled.unaliasedTransientBytes + compiled.persistentBytes;
    runs.resources = graphResourcesJson(frameGraph.graph, compiled);
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
// lands in the first frame (README, setup_ms).
void prepareFirstFrame(FrameBuilder::Setup setup, PipelineCache& pipelines, PhysicalResources& resources,
                       GraphExecutor& executor, const FrameBuffers& buffers) {
  compileAndRecord(buildFrameGraph(pipelines, setup, buffers).graph, resources, executor);
  if (!setup.historyWanted) return;
  setup.historyValid = true;
  setup.previousCamera = setup.camera;
  compileAndRecord(buildFrameGraph(pipelines, setup, buffers).graph, resources, executor);
}

// The format and layout of a technique's output, from a graph that is built and never run.
FrameGraph dryFrame(PipelineCache& pipelines, const FrameBuilder::Setup& setup) { return buildFrameGraph(pipelines, setup, {}); }

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

ReplayResult replayCapture(VulkanContext& vk, const Capture& capture, const ReplayOptions& options, const FrameSink& sink) {
  int total = int(capture.frames.size());
  int begin = options.frameBegin, end = options.frameEnd < 0 ? total : options.frameEnd;
  checkRange(capture, begin, end, total);
  checkTechnique(vk, capture, options);
  const Settings& settings = options.settings;
  const Technique& technique = settings.technique();
  bool historyWanted = historyNeedsOf(settings, end - begin).keeps;

  ReplayResult result;
  result.device = vk.info;
  result.settings = settings;
  auto setupStart = Clock::now();  // the origin of every start time in the result

  std::unique_ptr<TechniqueState> state;
  if (technique.prepare) state = technique.prepare(ReplaySetup{capture, settings, &vk});
  CaptureLayout layout{capture.hasNormals, capture.hasDepth2 && technique.inputs.depth2 != InputUse::Unused};
  auto frameCamera = [&capture](int index) {
    const auto& frame = capture.frames[size_t(index)];
    return FrameCamera{frame.view, frame.projection, capture.width, capture.height, uint32_t(index)};
  };
  auto setupFor = [&](int index, const FrameCamera& previous, bool valid) {
    FrameBuilder::Setup s;
    s.settings = &settings;
    s.camera = frameCamera(index);
    s.previousCamera = previous;
    s.capture = layout;
    s.historyWanted = historyWanted;
    s.historyValid = valid;
    s.debugViews = options.debugViews;
    s.state = state.get();
    return s;
  };
  PipelineCache pipelines(vk);
  FrameGraph dry = dryFrame(pipelines, setupFor(begin, {}, false));
  StagingBuffers staging(vk, capture, layout.depth2, graph::bytesPerPixel(dry.outputFormat));
  graph::ImageDesc outputDesc = dry.graph.resources()[dry.output].desc;

  // Runs on a worker while the GPU runs the previous frame from the other staging slot.
  auto decode = [&capture, &staging, historyWanted, setupStart](int index) {
    auto t = Clock::now();
    DecodedFrame d;
    d.startMs = msBetween(setupStart, t);
    d.gbuffer = loadGBuffer(capture, index);
    d.invalidDepthPixels = countInvalidDepth(d.gbuffer);
    if (historyWanted) d.medianDistance = medianViewDistance(d.gbuffer.depth, capture.frames[size_t(index)].projection);
    d.decodeMs = msSince(t);
    t = Clock::now();
    StagingSlot& slot = staging.forFrame(index);
    std::memcpy(slot.depth.mapped, d.gbuffer.depth.data(), d.gbuffer.depth.size() * sizeof(float));
    if (staging.normals) d.invalidNormalPixels = packNormals(d.gbuffer, static_cast<uint16_t*>(slot.normals.mapped));
    if (staging.depth2) std::memcpy(slot.depth2.mapped, d.gbuffer.depth2.data(), d.gbuffer.depth2.size() * sizeof(float));
    d.uploadMs = msSince(t);
    return d;
  };
  auto next = std::async(std::launch::async, decode, begin);  // overlaps the set-up below

  PhysicalResources resources(vk);
  GraphExecutor executor(vk);
  HistoryTracker history;
  auto frameBuffers = [&staging](int index) {
    StagingSlot& slot = staging.forFrame(index);
    return FrameBuffers{{&slot.depth, staging.normals ? &slot.normals : nullptr, staging.depth2 ? &slot.depth2 : nullptr},
                        &slot.readback};
  };
  auto withTargets = [&](FrameBuilder::Setup s, int index) {
    s.historyStates = historyStatesOf(resources);
    s.debugTarget = [&staging, index](const std::string& name, uint64_t bytes) { return staging.debugTarget(index, name, bytes); };
    return s;
  };
  prepareFirstFrame(withTargets(setupFor(begin, {}, false), begin), pipelines, resources, executor, frameBuffers(begin));
  result.setupMs = msSince(setupStart);
  auto replayStart = Clock::now();
  // A frame's sink (read-back conversion, image writing, analysis) runs on a worker thread while the
  // next frame runs on the GPU; sinks run one at a time, in frame order.
  struct SinkTimes {
    double startMs = 0, readbackMs = 0, writeMs = 0;
    std::vector<DebugCounters> counters;
  };
  std::future<SinkTimes> pendingSink;
  size_t pendingRecord = 0;
  auto finishPendingSink = [&] {
    if (!pendingSink.valid()) return;
    SinkTimes times = pendingSink.get();
    auto& record = result.frames[pendingRecord];
    record.sinkStartMs = times.startMs;
    record.readbackMs = times.readbackMs;
    record.writeMs = times.writeMs;
    record.debugCounters = std::move(times.counters);
  };

  for (int index = begin; index < end; ++index) {
    FrameRecord record;
    record.index = index;
    record.hostStartMs = msSince(setupStart);
    DecodedFrame decoded = next.get();
    record.workerStartMs = decoded.startMs;
    record.decodeMs = decoded.decodeMs;
    record.uploadMs = decoded.uploadMs;
    record.invalidDepthPixels = decoded.invalidDepthPixels;
    record.invalidNormalPixels = decoded.invalidNormalPixels;
    record.waitMs = msSince(setupStart) - record.hostStartMs;
    if (index + 1 < end) next = std::async(std::launch::async, decode, index + 1);

    const auto& frame = capture.frames[size_t(index)];
    FrameCamera camera = frameCamera(index);
    record.resetReason = history.resetReason(frame, capture.width, capture.height, settings, historyWanted, options);
    record.historyValid = record.resetReason.empty();
    if (history.exists && (history.width != capture.width || history.height != capture.height)) resources.dropHistory();

    auto setup = withTargets(setupFor(index, history.camera, record.historyValid), index);
    if (index == options.testPoisonHistoryAt && record.historyValid) poisonHistory(setup, outputDesc, resources, executor);
    bool lastFrame = index + 1 == end;
    auto runs = runFrameGraph(setup, pipelines, resources, executor, frameBuffers(index), options.warmup, options.repeat,
                              lastFrame);
    record.passes = std::move(runs.passes);
    record.recordMs = runs.recordMs;
    record.gpuWallMs = runs.gpuMs;
    if (lastFrame) {
      result.culled = std::move(runs.culled);
      result.graphDescription = std::move(runs.description);
      result.peakGpuBytes = runs.peakBytes;
      result.unaliasedGpuBytes = runs.unaliasedBytes;
      result.resources = std::move(runs.resources);
    }

    if (historyWanted) resources.swapHistory();
    history = {true, capture.width, capture.height, settings, camera, decoded.medianDistance};
    finishPendingSink();  // the previous frame's sink: its slot is the next frame's
    if (sink || !runs.debug.empty()) {
      pendingRecord = result.frames.size();  // the record pushed below
      StagingSlot& slot = staging.forFrame(index);
      pendingSink = std::async(std::launch::async, [&sink, &capture, &slot, index, setupStart, frame = std::move(decoded),
                                                    valid = record.historyValid, reason = record.resetReason,
                                                    format = runs.outputFormat, layout = runs.outputLayout,
                                                    debug = std::move(runs.debug)] {
        auto start = Clock::now();
        SinkTimes times;
        times.startMs = msBetween(setupStart, start);
        size_t pixels = size_t(capture.width) * size_t(capture.height);
        auto decodedOutput = decodeOutput(slot.readback.mapped, format, layout, pixels);
        FrameOutput output;
        output.index = index;
        output.width = capture.width;
        output.height = capture.height;
        output.visibility = std::move(decodedOutput.visibility);
        output.bent = std::move(decodedOutput.bent);
        for (const auto& d : debug) {
          if (!d.target) continue;
          if (d.format != VK_FORMAT_UNDEFINED) {
            DebugImage image{d.name, int(d.width), int(d.height), decodableChannels(d.format),
                             decodeTexels(d.target->mapped, d.format, size_t(d.width) * d.height)};
            output.debugImages.push_back(std::move(image));
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
        if (sink) sink(output);
        times.writeMs = msSince(written);
        return times;
      });
    }
    result.frames.push_back(std::move(record));
    if (options.progress) options.progress(index - begin + 1, end - begin);
  }
  finishPendingSink();
  result.wallMs = msSince(replayStart);
  return result;
}

}  // namespace aor
