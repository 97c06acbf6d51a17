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

#include "metrics/parallel_rows.h"
#include "pipeline/ao_graph.h"
#include "pipeline/graph_executor.h"
#include "pipeline/graph_resources.h"
#include "report/graph_json.h"

namespace aor {
namespace {

using Clock = std::chrono::steady_clock;
double msBetween(Clock::time_point from, Clock::time_point to) {
  return std::chrono::duration<double, std::milli>(to - from).count();
}
double msSince(Clock::time_point t) { return msBetween(t, Clock::now()); }

// Host-visible staging for one frame in flight: G-buffer uploads and the read-back of the result.
struct StagingSlot {
  GpuBuffer depth, normals, readback;
};

// Two slots, used by alternate frames: while the GPU runs frame N from one slot, the decode worker
// fills the other with frame N+1, and the sink of frame N-1 reads its result from the read-back of
// that same other slot (before frame N+1 is submitted). Destroyed in one place.
struct StagingBuffers {
  VulkanContext& vk;
  StagingSlot slots[2];
  StagingBuffers(VulkanContext& v, const Capture& capture, bool bent) : vk(v) {
    VkDeviceSize pixels = VkDeviceSize(capture.width) * VkDeviceSize(capture.height);
    for (auto& slot : slots) {
      slot.depth = createHostBuffer(vk, pixels * sizeof(float), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
      if (capture.hasNormals)
        slot.normals = createHostBuffer(vk, pixels * 4 * sizeof(uint16_t), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
      slot.readback = createHostBuffer(vk, pixels * graph::bytesPerPixel(aoFormat(bent)), VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    }
  }
  ~StagingBuffers() {
    for (auto& slot : slots) {
      destroyBuffer(vk, slot.depth);
      destroyBuffer(vk, slot.normals);
      destroyBuffer(vk, slot.readback);
    }
  }
  StagingSlot& forFrame(int index) { return slots[index % 2]; }
};

// A frame made ready for the GPU on the worker thread: decoded, inputs checked and written into its
// staging slot, so the replay thread only records and submits.
struct DecodedFrame {
  GBuffer gbuffer;
  int64_t invalidDepthPixels = 0, invalidNormalPixels = 0;
  float medianDistance = 0;  // for the camera-jump limit; 0 when there is no temporal pass
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

// Every half-float bit pattern converted once (by the same glm function, so results are identical):
// the read-back converts 4 halves per pixel, and a table lookup is several times cheaper.
const std::vector<float>& halfToFloat() {
  static const std::vector<float> table = [] {
    std::vector<float> t(65536);
    for (uint32_t h = 0; h < 65536; ++h) t[h] = glm::unpackHalf1x16(uint16_t(h));
    return t;
  }();
  return table;
}

// Converted to floats by the frame's sink worker straight from the mapped read-back of its slot,
// which no frame overwrites before the sink has finished (StagingBuffers).
FrameOutput decodeReadback(const GpuBuffer& readback, int index, int width, int height, bool bent) {
  FrameOutput out;
  out.index = index;
  out.width = width;
  out.height = height;
  size_t pixels = size_t(width) * size_t(height);
  const auto* halves = static_cast<const uint16_t*>(readback.mapped);
  const float* toFloat = halfToFloat().data();
  out.visibility.resize(pixels);
  if (bent) out.bent.resize(pixels * 3);
  for (size_t i = 0; i < pixels; ++i) {
    if (!bent) {
      out.visibility[i] = toFloat[halves[i]];
      continue;
    }
    for (size_t c = 0; c < 3; ++c) out.bent[3 * i + c] = toFloat[halves[4 * i + c]];
    out.visibility[i] = toFloat[halves[4 * i + 3]];
  }
  return out;
}

struct HistoryTracker {
  bool exists = false;
  int width = 0, height = 0;
  AoSettings settings;
  FrameCamera camera;
  float medianDistance = 0;  // of the frame it holds, for the camera-jump limit

  // Why the previous frame's output must not be blended into this one; empty when it may.
  std::string resetReason(const CaptureFrame& frame, int width, int height, const AoSettings& settings, bool temporalWanted,
                          const ReplayOptions& options) const {
    if (!temporalWanted) return settings.temporal <= 0.0f ? "temporal=0" : "single-frame replay";
    if (!exists) return "first frame";
    if (frame.cut && !options.keepHistoryOnCut) return "cut";
    if (width != this->width || height != this->height) return "size change";
    if (!(settings == this->settings)) return "settings changed";
    if (frame.cut && options.keepHistoryOnCut) return {};  // test-only: the cut's jump must not reset either
    return cameraJumpReason(camera.view, frame.view, medianDistance, options.cameraJump);
  }
};

HistoryStates historyStatesOf(const GraphResources& resources) {
  return [&resources](const std::string& base, bool current) { return resources.historyState(base, current); };
}

// Compiles `graph` and records it into the executor's command buffer with its physical images.
graph::CompiledGraph compileAndRecord(const graph::RenderGraph& graph, GraphResources& resources, GraphExecutor& executor) {
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

  std::vector<CulledPassInfo> culled;
  std::string description;
  uint64_t peakBytes = 0, unaliasedBytes = 0;
  nlohmann::json resources;
};

// Executes the frame's graph `warmup + repeat` times (only the last `repeat` are timed). The graph
// is rebuilt per run: each run starts from the image states the previous one left.
FrameGraphRuns runFrameGraph(const AoFrameInputs& inputs, PassPipelines& pipelines, GraphResources& resources,
                             GraphExecutor& executor, const AoFrameBuffers& buffers, int warmup, int repeat,
                             bool describeGraph) {
  FrameGraphRuns runs;
  for (int run = 0; run < warmup + repeat; ++run) {
    auto start = Clock::now();
    auto frameGraph = buildAoFrameGraph(inputs, pipelines, historyStatesOf(resources), buffers);
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

// Test-only (ReplayOptions::testPoisonHistoryAt): overwrites the AO history the next frame reads
// with NaN, through the graph so the barriers stay derived.
void poisonAoHistory(const AoFrameInputs& inputs, GraphResources& resources, GraphExecutor& executor) {
  auto poison = buildHistoryPoisonGraph(inputs, historyStatesOf(resources), std::numeric_limits<float>::quiet_NaN());
  auto compiled = compileAndRecord(poison, resources, executor);
  executor.submitAndWait();
  resources.keepFinalStates(poison, compiled);
}

// Set-up, outside the replay's wall time as device creation is: the first frame's graph is recorded
// once and not submitted, which creates the pipelines of its live passes and its images, and the
// temporal pass's with-history variant, which every later frame uses, is created directly. Pipeline
// creation (about 17 ms on lavapipe) then never lands in a frame's time; lavapipe's compile to
// machine code happens at a shader's first dispatch, so there that part still lands in the first
// frame (README, setup_ms).
void prepareFirstFrame(const AoFrameInputs& inputs, PassPipelines& pipelines, GraphResources& resources,
                       GraphExecutor& executor, const AoFrameBuffers& buffers) {
  compileAndRecord(buildAoFrameGraph(inputs, pipelines, historyStatesOf(resources), buffers).graph, resources, executor);
  if (inputs.temporalWanted) pipelines.temporal(inputs.settings.bent != 0, true, inputs.settings.halfRes != 0);
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

AoSettings settingsForCapture(const Capture& capture, const AoSettings& base, bool radiusGiven) {
  AoSettings s = base;
  if (!radiusGiven && capture.scene.contains("ao_radius") && capture.scene["ao_radius"].is_number()) {
    double r = capture.scene["ao_radius"].get<double>();
    if (!(r > 0.0 && std::isfinite(r)))
      throw InputError((capture.folder / "capture.json").string(), std::nullopt, "scene.ao_radius",
                       fmt::format("must be a positive number, got {}", r));
    s.radius = float(r);
  }
  return s;
}

ReplayResult replayCapture(VulkanContext& vk, const Capture& capture, const ReplayOptions& options, const FrameSink& sink) {
  int total = int(capture.frames.size());
  int begin = options.frameBegin, end = options.frameEnd < 0 ? total : options.frameEnd;
  if (begin < 0 || begin >= end || end > total)
    throw InputError((capture.folder / "capture.json").string(), std::nullopt, "--frames",
                     fmt::format("range {}:{} is not inside the capture's {} frames (half-open A:B with 0 <= A < B <= {})",
                                 begin, end, total, total));
  const auto& settings = options.settings;
  bool bent = settings.bent != 0;
  bool temporalWanted = end - begin > 1 && settings.temporal > 0.0f;

  ReplayResult result;
  result.device = vk.info;
  result.settings = settings;
  auto setupStart = Clock::now();  // the origin of every start time in the result

  StagingBuffers staging(vk, capture, bent);
  // Runs on a worker while the GPU runs the previous frame from the other staging slot.
  auto decode = [&capture, &staging, temporalWanted, setupStart](int index) {
    auto t = Clock::now();
    DecodedFrame d;
    d.startMs = msBetween(setupStart, t);
    d.gbuffer = loadGBuffer(capture, index);
    d.invalidDepthPixels = countInvalidDepth(d.gbuffer);
    if (temporalWanted) d.medianDistance = medianViewDistance(d.gbuffer.depth, capture.frames[size_t(index)].projection);
    d.decodeMs = msSince(t);
    t = Clock::now();
    StagingSlot& slot = staging.forFrame(index);
    std::memcpy(slot.depth.mapped, d.gbuffer.depth.data(), d.gbuffer.depth.size() * sizeof(float));
    if (capture.hasNormals) d.invalidNormalPixels = packNormals(d.gbuffer, static_cast<uint16_t*>(slot.normals.mapped));
    d.uploadMs = msSince(t);
    return d;
  };
  auto next = std::async(std::launch::async, decode, begin);  // overlaps the set-up below

  PassPipelines pipelines(vk);
  GraphResources resources(vk);
  GraphExecutor executor(vk);
  HistoryTracker history;
  auto frameCamera = [&capture](int index) {
    const auto& frame = capture.frames[size_t(index)];
    return FrameCamera{frame.view, frame.projection, capture.width, capture.height, uint32_t(index)};
  };
  auto frameBuffers = [&staging, &capture](int index) {
    StagingSlot& slot = staging.forFrame(index);
    return AoFrameBuffers{&slot.depth, capture.hasNormals ? &slot.normals : nullptr, &slot.readback};
  };
  prepareFirstFrame({frameCamera(begin), {}, capture.hasNormals, temporalWanted, false, settings}, pipelines, resources,
                    executor, frameBuffers(begin));
  result.setupMs = msSince(setupStart);
  auto replayStart = Clock::now();
  // A frame's sink (read-back conversion, image writing, analysis) runs on a worker thread while the
  // next frame runs on the GPU; sinks run one at a time, in frame order.
  struct SinkTimes {
    double startMs = 0, readbackMs = 0, writeMs = 0;
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
    record.resetReason = history.resetReason(frame, capture.width, capture.height, settings, temporalWanted, options);
    record.historyValid = record.resetReason.empty();
    if (history.exists && (history.width != capture.width || history.height != capture.height)) resources.dropHistory();

    AoFrameInputs inputs{camera, history.camera, capture.hasNormals, temporalWanted, record.historyValid, settings};
    StagingSlot& slot = staging.forFrame(index);
    if (index == options.testPoisonHistoryAt && record.historyValid) poisonAoHistory(inputs, resources, executor);
    bool lastFrame = index + 1 == end;
    auto runs = runFrameGraph(inputs, pipelines, resources, executor, frameBuffers(index), options.warmup,
                              options.repeat, lastFrame);
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

    if (temporalWanted) resources.swapHistory();
    history = {true, capture.width, capture.height, settings, camera, decoded.medianDistance};
    finishPendingSink();  // the previous frame's sink: its slot is the next frame's
    if (sink) {
      pendingRecord = result.frames.size();  // the record pushed below
      pendingSink = std::async(std::launch::async, [&sink, &capture, &slot, bent, index, setupStart,
                                                    frame = std::move(decoded), valid = record.historyValid,
                                                    reason = record.resetReason] {
        auto start = Clock::now();
        SinkTimes times;
        times.startMs = msBetween(setupStart, start);
        FrameOutput output = decodeReadback(slot.readback, index, capture.width, capture.height, bent);
        times.readbackMs = msSince(start);
        auto written = Clock::now();
        output.gbuffer = &frame.gbuffer;
        output.historyValid = valid;
        output.resetReason = reason;
        sink(output);
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
