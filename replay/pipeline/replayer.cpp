#include "pipeline/replayer.h"

#include <chrono>
#include <cmath>
#include <cstring>
#include <future>
#include <memory>

#include <fmt/format.h>
#include <glm/gtc/packing.hpp>

#include "pipeline/ao_graph.h"
#include "pipeline/graph_executor.h"
#include "pipeline/graph_resources.h"
#include "report/graph_json.h"

namespace aor {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

// A frame made ready for the GPU on the worker thread: decoded, normals packed to the staging
// layout, inputs checked, so the main thread only copies while the GPU waits.
struct DecodedFrame {
  GBuffer gbuffer;
  std::vector<uint16_t> packedNormals;  // RGBA16F, empty without normals
  int64_t invalidDepthPixels = 0, invalidNormalPixels = 0;
  float medianDistance = 0;  // for the camera-jump limit; 0 when there is no temporal pass
  double decodeMs = 0;
};

// Host-visible staging: G-buffer uploads and the read-back of the result. Destroyed in one place.
struct StagingBuffers {
  VulkanContext& vk;
  GpuBuffer depth, normals, readback;
  StagingBuffers(VulkanContext& v, const Capture& capture, bool bent) : vk(v) {
    VkDeviceSize pixels = VkDeviceSize(capture.width) * VkDeviceSize(capture.height);
    depth = createHostBuffer(vk, pixels * sizeof(float), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    if (capture.hasNormals) normals = createHostBuffer(vk, pixels * 4 * sizeof(uint16_t), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    readback = createHostBuffer(vk, pixels * graph::bytesPerPixel(aoFormat(bent)), VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  }
  ~StagingBuffers() {
    destroyBuffer(vk, depth);
    destroyBuffer(vk, normals);
    destroyBuffer(vk, readback);
  }
};

int64_t countInvalidDepth(const GBuffer& g) {
  int64_t invalid = 0;
  for (float d : g.depth) invalid += !(d >= 0.0f && d <= 1.0f);  // NaN fails both comparisons
  return invalid;
}

int64_t packNormals(const GBuffer& g, std::vector<uint16_t>& packed) {
  size_t pixels = g.normals.size() / 3;
  packed.resize(pixels * 4);
  uint16_t* out = packed.data();
  int64_t invalid = 0;
  for (size_t i = 0; i < pixels; ++i) {
    bool finite = true;
    for (int c = 0; c < 3; ++c) {
      float v = g.normals[3 * i + size_t(c)];
      finite &= std::isfinite(v);
      out[4 * i + size_t(c)] = glm::packHalf1x16(v);
    }
    out[4 * i + 3] = 0;
    invalid += !finite;
  }
  return invalid;
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

// The read-back is copied out of the mapped buffer on the replay thread (the next frame overwrites
// it) and converted to floats by the frame's sink worker, off the critical path.
std::vector<uint16_t> copyReadback(const GpuBuffer& readback, int width, int height, bool bent) {
  size_t count = size_t(width) * size_t(height) * (bent ? 4 : 1);
  const auto* halves = static_cast<const uint16_t*>(readback.mapped);
  return std::vector<uint16_t>(halves, halves + count);
}

FrameOutput decodeReadback(const std::vector<uint16_t>& raw, int index, int width, int height, bool bent) {
  FrameOutput out;
  out.index = index;
  out.width = width;
  out.height = height;
  size_t pixels = size_t(width) * size_t(height);
  const uint16_t* halves = raw.data();
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


// What running one frame's graph gives back: timings of the timed runs and, when asked, the facts
// of its compiled graph that the report records.
struct FrameGraphRuns {
  std::vector<PassTiming> passes;
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
    auto frameGraph = buildAoFrameGraph(inputs, pipelines, &resources, buffers);
    auto compiled = frameGraph.graph.compile();
    executor.record(frameGraph.graph, compiled, resources.prepare(frameGraph.graph, compiled));
    auto times = executor.submitAndWait();
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

}  // namespace

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
  auto replayStart = Clock::now();

  auto decode = [&capture, temporalWanted](int index) {
    auto t = Clock::now();
    DecodedFrame d;
    d.gbuffer = loadGBuffer(capture, index);
    d.invalidDepthPixels = countInvalidDepth(d.gbuffer);
    if (capture.hasNormals) d.invalidNormalPixels = packNormals(d.gbuffer, d.packedNormals);
    if (temporalWanted) d.medianDistance = medianViewDistance(d.gbuffer.depth, capture.frames[size_t(index)].projection);
    d.decodeMs = msSince(t);
    return d;
  };
  auto next = std::async(std::launch::async, decode, begin);  // overlaps the set-up below

  PassPipelines pipelines(vk);
  GraphResources resources(vk);
  GraphExecutor executor(vk);
  StagingBuffers staging(vk, capture, bent);
  AoFrameBuffers buffers{&staging.depth, capture.hasNormals ? &staging.normals : nullptr, &staging.readback};
  HistoryTracker history;
  // A frame's sink (image writing, analysis) runs on a worker thread while the next frame is
  // uploaded and run on the GPU; sinks run one at a time, in frame order. Its time is the frame's
  // write time.
  std::future<double> pendingSink;
  size_t pendingRecord = 0;
  auto finishPendingSink = [&] {
    if (pendingSink.valid()) result.frames[pendingRecord].writeMs = pendingSink.get();
  };

  for (int index = begin; index < end; ++index) {
    FrameRecord record;
    record.index = index;
    record.hostStartMs = msSince(replayStart);
    DecodedFrame decoded = next.get();
    record.decodeMs = decoded.decodeMs;
    if (index + 1 < end) next = std::async(std::launch::async, decode, index + 1);

    auto t = Clock::now();
    std::memcpy(staging.depth.mapped, decoded.gbuffer.depth.data(), decoded.gbuffer.depth.size() * sizeof(float));
    if (capture.hasNormals)
      std::memcpy(staging.normals.mapped, decoded.packedNormals.data(), decoded.packedNormals.size() * sizeof(uint16_t));
    record.invalidDepthPixels = decoded.invalidDepthPixels;
    record.invalidNormalPixels = decoded.invalidNormalPixels;
    record.uploadMs = msSince(t);

    const auto& frame = capture.frames[size_t(index)];
    FrameCamera camera{frame.view, frame.projection, capture.width, capture.height, uint32_t(index)};
    record.resetReason = history.resetReason(frame, capture.width, capture.height, settings, temporalWanted, options);
    record.historyValid = record.resetReason.empty();
    if (history.exists && (history.width != capture.width || history.height != capture.height)) resources.dropHistory();

    AoFrameInputs inputs{camera, history.camera, capture.hasNormals, temporalWanted, record.historyValid, settings};
    t = Clock::now();
    bool lastFrame = index + 1 == end;
    auto runs = runFrameGraph(inputs, pipelines, resources, executor, buffers, options.warmup, options.repeat, lastFrame);
    record.passes = std::move(runs.passes);
    if (lastFrame) {
      result.culled = std::move(runs.culled);
      result.graphDescription = std::move(runs.description);
      result.peakGpuBytes = runs.peakBytes;
      result.unaliasedGpuBytes = runs.unaliasedBytes;
      result.resources = std::move(runs.resources);
    }
    record.gpuWallMs = msSince(t);

    t = Clock::now();
    std::vector<uint16_t> readback = sink ? copyReadback(staging.readback, capture.width, capture.height, bent)
                                          : std::vector<uint16_t>();
    record.readbackMs = msSince(t);

    if (temporalWanted) resources.swapHistory();
    history = {true, capture.width, capture.height, settings, camera, decoded.medianDistance};
    finishPendingSink();
    if (sink) {
      pendingRecord = result.frames.size();  // the record pushed below
      pendingSink = std::async(std::launch::async, [&sink, &capture, bent, index, raw = std::move(readback),
                                                    frame = std::move(decoded), valid = record.historyValid,
                                                    reason = record.resetReason] {
        auto start = Clock::now();
        FrameOutput output = decodeReadback(raw, index, capture.width, capture.height, bent);
        output.gbuffer = &frame.gbuffer;
        output.historyValid = valid;
        output.resetReason = reason;
        sink(output);
        return msSince(start);
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
