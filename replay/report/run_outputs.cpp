#include "report/run_outputs.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <fstream>

#include <fmt/format.h>

#include "capture/content_hash.h"
#include "core/version.h"
#include "capture/image_io.h"
#include "core/pass_names.h"
#include "graph/graph_json.h"
#include "core/stats.h"

namespace aor {
namespace fs = std::filesystem;

namespace {

nlohmann::json summaryJson(const Summary& s) {
  return {{"min", s.min}, {"median", s.median}, {"max", s.max}, {"mean", s.mean}, {"count", s.count}};
}

double sumOf(const std::vector<double>& values) { return std::accumulate(values.begin(), values.end(), 0.0); }

// report.json's counted cost: per pass the counts of each frame and their total, the run's totals
// (compute passes; host copies apart) and what the counts depend on.
void addCountedCost(nlohmann::json& report, const ReplayOptions& options, const ReplayResult& result) {
  const std::string key = costMeasureName(options.cost);
  nlohmann::json passes = nlohmann::json::array();
  double compute = 0, copies = 0;
  for (const auto& [name, perFrame] : countsByPass(result, options.cost)) {
    passes.push_back({{"name", name}, {key, {{"total", sumOf(perFrame)}, {"per_frame", perFrame}}}});
    (isHostCopyPass(name) ? copies : compute) += sumOf(perFrame);
  }
  report["passes"] = passes;
  report[key + "_total"] = compute;
  report[key + "_host_copies_total"] = copies;
  report["cost"] = costDependencies(options.cost, result.device);
}

// report.json's GPU time: per pass its summary and every sample, and the run's totals.
void addTimedCost(nlohmann::json& report, const ReplayResult& result) {
  nlohmann::json passes = nlohmann::json::array();
  for (const auto& [name, samples] : samplesByPass(result)) {
    auto gpuMs = summaryJson(summarize(samples));
    gpuMs["samples"] = samples;  // every timed run, frame-major: what `aoreplay compare` tests
    passes.push_back({{"name", name}, {"gpu_ms", gpuMs}});
  }
  report["passes"] = passes;
  auto frames = timedFrames(result);
  report["gpu_ms_total_median"] = totalMedianMs(frames, PassGroup::Compute);
  report["gpu_ms_host_copies_median"] = totalMedianMs(frames, PassGroup::HostCopies);
}

nlohmann::json framePassesJson(const FrameRecord& f, CostMeasure measure) {
  nlohmann::json passes = nlohmann::json::object();
  for (const auto& p : f.passes)
    passes[p.name] = measure == CostMeasure::Time ? summarize(p.durationsMs).median : costOf(measure, p.counts);
  return passes;
}

}  // namespace

nlohmann::json costDependencies(CostMeasure measure, const DeviceInfo& device) {
  nlohmann::json cost{{"measure", costMeasureName(measure)},
                      {"device", device.name},
                      {"driver", device.driverInfo},
                      {"cpu", countedCpuName()},
                      {"valgrind", countedValgrindVersion()},
                      {"excluded", "the C library's allocator and thread synchronisation"}};
  std::string key;
  for (const char* k : {"measure", "device", "driver", "cpu", "valgrind"}) key += cost[k].get<std::string>() + "|";
  if (measure == CostMeasure::Cycles) {
    cost["cache"] = {{"I1", kCostCacheI1}, {"D1", kCostCacheD1}, {"LL", kCostCacheLL}};
    cost["formula"] = kCyclesFormula;
    key += std::string(kCostCacheI1) + "/" + kCostCacheD1 + "/" + kCostCacheLL;
  }
  cost["key"] = key;
  return cost;
}


void writeFrameImages(const fs::path& outDir, const FrameOutput& frame) {
  fs::create_directories(outDir / "ao");
  auto stem = outDir / "ao" / fmt::format("{:04d}", frame.index);
  std::vector<ExrChannel> channels{{"visibility", ExrPixelType::Float, frame.visibility.data()}};
  std::vector<float> bentPlanes[3];
  if (!frame.bent.empty()) {
    const char* names[] = {"bent.X", "bent.Y", "bent.Z"};
    for (size_t c = 0; c < 3; ++c) {
      bentPlanes[c].resize(frame.visibility.size());
      for (size_t i = 0; i < bentPlanes[c].size(); ++i) bentPlanes[c][i] = frame.bent[3 * i + c];
      channels.push_back({names[c], ExrPixelType::Float, bentPlanes[c].data()});
    }
  }
  writeExr(stem.string() + ".exr", frame.width, frame.height, channels);
  writePngGray(stem.string() + ".png", frame.width, frame.height, frame.visibility.data());
}

void writeDebugImage(const fs::path& outDir, int frameIndex, const DebugImage& view) {
  fs::create_directories(outDir / "debug" / view.name);
  auto stem = outDir / "debug" / view.name / fmt::format("{:04d}", frameIndex);
  static const char* kChannelNames[] = {"R", "G", "B", "A"};
  size_t texels = size_t(view.width) * size_t(view.height);
  std::vector<std::vector<float>> planes(view.channels, std::vector<float>(texels));
  std::vector<ExrChannel> channels;
  for (uint32_t c = 0; c < view.channels; ++c) {
    for (size_t i = 0; i < texels; ++i) planes[c][i] = view.values[i * view.channels + c];
    channels.push_back({kChannelNames[c], ExrPixelType::Float, planes[c].data()});
  }
  writeExr(stem.string() + ".exr", view.width, view.height, channels);
  // The preview stretches the first channel's finite range to grey, so depths and counts are visible too.
  float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
  for (float v : planes[0])
    if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  std::vector<float> grey(texels, 0.0f);
  if (hi > lo)
    for (size_t i = 0; i < texels; ++i) grey[i] = std::isfinite(planes[0][i]) ? (planes[0][i] - lo) / (hi - lo) : 0.0f;
  writePngGray(stem.string() + ".png", view.width, view.height, grey.data());
}

nlohmann::json buildReport(const Capture& capture, const ReplayOptions& options, const ReplayResult& result) {
  nlohmann::json report;
  report["tool"] = "aoreplay";
  report["tool_version"] = aoreplayVersion();
  // content_sha256 keys the run's series in a results store (aoreplay record), wherever the capture lies.
  report["capture"] = {{"path", capture.folder.string()}, {"name", capture.name},
                       {"content_sha256", captureContentSha256(capture)}, {"width", capture.width},
                       {"height", capture.height}, {"frames", capture.frames.size()},
                       {"has_normals", capture.hasNormals}, {"has_depth2", capture.hasDepth2}};
  report["device"] = {{"name", result.device.name}, {"driver", result.device.driver}, {"api_version", result.device.apiVersion}};
  report["settings"] = result.settings.toJson();
  report["run"] = {{"frames", {options.frameBegin, options.frameBegin + int(result.frames.size())}},
                   {"repeat", options.repeat}, {"warmup", options.warmup}};
  // A user technique's technique.json, as --technique named it (user_techniques/FORMAT.md).
  if (const auto& file = result.settings.technique().file; !file.empty()) report["run"]["technique_file"] = file;
  report["timing"] = {{"mode", timingModeName(result.timingMode)},
                      {"preload_budget_mib", double(options.preloadBudgetBytes) / double(1 << 20)},
                      {"chunk_frames", result.chunkFrames}};

  if (options.cost == CostMeasure::Time) addTimedCost(report, result);
  else addCountedCost(report, options, result);
  nlohmann::json culled = nlohmann::json::array();
  for (const auto& c : result.culled) culled.push_back({{"name", c.name}, {"reason", c.reason}});
  report["culled_passes"] = culled;
  const graph::CompiledGraph& compiled = result.graph.compiled;
  report["memory"] = {{"peak_gpu_bytes", compiled.peakBytes()},
                      {"unaliased_gpu_bytes", compiled.unaliasedTransientBytes + compiled.persistentBytes},
                      {"resources", graphResourcesJson(result.graph.declared, compiled)}};

  nlohmann::json frameList = nlohmann::json::array();
  for (const auto& f : result.frames) {
    nlohmann::json frame{{"index", f.index}, {"history", f.historyValid ? "valid" : "reset"}};
    if (!f.historyValid) frame["reset_reason"] = f.resetReason;
    frame[options.cost == CostMeasure::Time ? "gpu_ms_median" : costMeasureName(options.cost)] = framePassesJson(f, options.cost);
    frame["host_ms"] = {{"decode", f.decodeMs}, {"upload", f.uploadMs},     {"wait", f.waitMs},
                        {"record", f.recordMs}, {"gpu", f.gpuWallMs},       {"readback", f.readbackMs},
                        {"write", f.writeMs}};
    if (!f.debugCounters.empty()) {
      nlohmann::json debug = nlohmann::json::object();
      for (const auto& c : f.debugCounters) debug[c.name] = c.values;
      frame["debug"] = debug;
    }
    if (!f.techniqueValues.empty()) frame["technique"] = f.techniqueValues;
    frame["invalid_depth_pixels"] = f.invalidDepthPixels;
    frame["invalid_normal_pixels"] = f.invalidNormalPixels;
    frameList.push_back(frame);
  }
  report["frames"] = frameList;
  if (!result.techniqueState.empty()) {
    nlohmann::json state = nlohmann::json::object();
    for (const auto& [key, value] : result.techniqueState) state[key] = value;
    report["technique_state"] = state;
  }
  report["setup_ms"] = result.setupMs;
  report["wall_ms"] = result.wallMs;
  report["replay_fps"] = result.wallMs > 0 ? 1000.0 * double(result.frames.size()) / result.wallMs : 0.0;
  HostOverhead overhead = hostOverhead(result);
  report["host_overhead"] = {{"ms", overhead.ms}, {"fraction_of_wall", overhead.fractionOfWall}};
  return report;
}

nlohmann::json buildReport(const Capture& capture, const ReplayOptions& options, const RunResults& run) {
  nlohmann::json report = buildReport(capture, options, run.replay);
  for (auto& frame : report["frames"])
    if (auto metrics = run.analysis.frameJson(frame["index"].get<int>()); !metrics.empty()) frame["metrics"] = metrics;
  report["metrics"] = run.analysis.summaryJson();
  return report;
}

nlohmann::json buildTrace(const ReplayResult& result) {
  constexpr int kPid = 1, kGpuTrack = 1, kHostTrack = 2, kWorkerTrack = 3, kSinkTrack = 4;
  nlohmann::json events = nlohmann::json::array();
  auto track = [&](int tid, const char* name) {
    events.push_back({{"name", "thread_name"}, {"ph", "M"}, {"pid", kPid}, {"tid", tid}, {"args", {{"name", name}}}});
  };
  track(kGpuTrack, "GPU passes");
  track(kHostTrack, "Host: replay thread");
  // Isolated timing runs decode and sink on the replay thread, around each chunk's GPU work.
  bool isolated = result.timingMode == TimingMode::Isolated;
  track(kWorkerTrack, isolated ? "Host: preload (replay thread, before the chunk's GPU work)" : "Host: decode worker");
  track(kSinkTrack, isolated ? "Host: sink (replay thread, after the chunk's GPU work)" : "Host: sink worker");
  auto slice = [&](const std::string& name, int track, double startMs, double durMs, nlohmann::json args) {
    events.push_back({{"name", name}, {"ph", "X"}, {"pid", kPid}, {"tid", track}, {"ts", startMs * 1000.0},
                      {"dur", durMs * 1000.0}, {"args", std::move(args)}});
  };
  slice("set-up (staging, pipelines, first frame's images)", kHostTrack, 0.0, result.setupMs, nlohmann::json::object());
  for (const auto& f : result.frames) {
    nlohmann::json args{{"frame", f.index}};
    slice("decode", kWorkerTrack, f.workerStartMs, f.decodeMs, args);
    slice("upload (staging write)", kWorkerTrack, f.workerStartMs + f.decodeMs, f.uploadMs, args);
    double t = f.hostStartMs;
    if (f.waitMs > 0) slice("wait for decode", kHostTrack, t, f.waitMs, args);
    t += f.waitMs;
    slice("record", kHostTrack, t, f.recordMs, args);  // with warm-up or repeats: all runs' recording, then all GPU waits
    t += f.recordMs;
    double gpuStart = t;
    slice("gpu (submit + wait)", kHostTrack, t, f.gpuWallMs, args);
    if (f.readbackMs + f.writeMs > 0) {
      slice("readback (to float)", kSinkTrack, f.sinkStartMs, f.readbackMs, args);
      slice("write", kSinkTrack, f.sinkStartMs + f.readbackMs, f.writeMs, args);
    }
    // GPU passes of the last timed run, placed at the end of the GPU wait window.
    double lastEnd = 0;
    for (const auto& p : f.passes) lastEnd = std::max(lastEnd, p.startMs + (p.durationsMs.empty() ? 0 : p.durationsMs.back()));
    double gpuOrigin = gpuStart + std::max(0.0, f.gpuWallMs - lastEnd);
    for (const auto& p : f.passes)
      if (!p.durationsMs.empty()) slice(p.name, kGpuTrack, gpuOrigin + p.startMs, p.durationsMs.back(), args);
  }
  return {{"traceEvents", events}, {"displayTimeUnit", "ms"}};
}

void writeText(const fs::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out) throw std::runtime_error(fmt::format("cannot write {}", path.string()));
}

void writeJson(const fs::path& path, const nlohmann::json& json) { writeText(path, json.dump(2) + "\n"); }

std::string countedPassTable(const ReplayResult& result, CostMeasure measure) {
  const char* name = costMeasureName(measure);
  std::string table = fmt::format("{:<22} {:>16} {:>16} {:>7}\n", "pass", fmt::format("{} total", name), "per frame max",
                                  "frames");
  double compute = 0;
  for (const auto& [pass, perFrame] : countsByPass(result, measure)) {
    table += fmt::format("{:<22} {:>16.0f} {:>16.0f} {:>7}\n", pass, sumOf(perFrame),
                         *std::max_element(perFrame.begin(), perFrame.end()), perFrame.size());
    if (!isHostCopyPass(pass)) compute += sumOf(perFrame);
  }
  return table + fmt::format("{:<22} {:>16.0f}\ntotal: the compute passes' {} over the frames, counted under callgrind "
                             "(host copies apart; the C library's allocator and locks left out)\n",
                             "total", compute, name);
}

std::string passTable(const ReplayResult& result) {
  auto row = [](const std::string& name, const Summary& s) {
    return fmt::format("{:<22} {:>10.3f} {:>10.3f} {:>10.3f} {:>8}\n", name, s.min, s.median, s.max, s.count);
  };
  std::string table = fmt::format("{:<22} {:>10} {:>10} {:>10} {:>8}\n", "pass", "min ms", "median ms", "max ms", "runs");
  for (const auto& [name, samples] : samplesByPass(result)) table += row(name, summarize(samples));
  auto frames = timedFrames(result);
  table += row("total", summarize(repetitionSumsMs(frames, PassGroup::Compute)));
  table += fmt::format("total: per timed run, the sum of the compute passes; host copies add {:.3f} (median)\n",
                       totalMedianMs(frames, PassGroup::HostCopies));
  return table;
}

}  // namespace aor
