#include "run/run.h"

#include <algorithm>

#include <fmt/format.h>

#include "run/analyzed_output.h"
#include "techniques/built_frame.h"
#include "techniques/registry.h"

namespace aor {
namespace {

int frameEnd(const Capture& capture, const ReplayOptions& options) {
  return options.frameEnd < 0 ? int(capture.frames.size()) : options.frameEnd;
}

bool everyFrameReferenced(const Capture& capture, int begin, int end) {
  for (int i = begin; i < end; ++i)
    if (!capture.frames[size_t(i)].reference) return false;
  return true;
}

// Without references, ghosting is measured against the same frames replayed without history (the
// technique's own no-history variant: one extra untimed replay, only for runs that keep history and
// techniques that have one).
std::map<int, std::vector<float>> replayWithoutHistory(VulkanContext& vk, const Capture& capture, const ReplayOptions& run) {
  std::map<int, std::vector<float>> frames;
  int end = frameEnd(capture, run);
  const Technique& technique = run.settings.technique();
  if (everyFrameReferenced(capture, run.frameBegin, end) || !historyNeedsOf(run.settings, end - run.frameBegin).keeps ||
      !technique.withoutHistory)
    return frames;
  auto without = technique.withoutHistory(run.settings);
  if (!without) return frames;
  ReplayOptions options(*without);
  options.frameBegin = run.frameBegin;
  options.frameEnd = run.frameEnd;
  replayCapture(vk, capture, options, [&](const FrameOutput& f) { frames[f.index] = f.visibility; });
  return frames;
}

// The weight of history in the technique's moving average, which the EMA prediction of ghosting uses.
float blendWeightOf(const Settings& settings) {
  const Technique& technique = settings.technique();
  return technique.history ? technique.history(settings).blendWeight : 0.0f;
}

const std::vector<float>* referenceOf(const Capture& capture, const References* given, int index,
                                      std::optional<std::vector<float>>& loaded) {
  if (given) {
    auto it = given->frames.find(index);
    return it == given->frames.end() ? nullptr : &it->second;
  }
  loaded = loadReference(capture, index);
  return loaded ? &*loaded : nullptr;
}

}  // namespace

std::vector<std::pair<std::string, std::vector<double>>> samplesByPass(const ReplayResult& result) {
  std::vector<std::pair<std::string, std::vector<double>>> passes;
  for (const auto& frame : result.frames)
    for (const auto& p : frame.passes) {
      auto it = std::find_if(passes.begin(), passes.end(), [&](const auto& e) { return e.first == p.name; });
      if (it == passes.end()) it = passes.insert(passes.end(), {p.name, {}});
      it->second.insert(it->second.end(), p.durationsMs.begin(), p.durationsMs.end());
    }
  return passes;
}

TimedFrame timedFrame(const FrameRecord& frame) {
  TimedFrame timed;
  for (const auto& p : frame.passes) timed.push_back({p.name, p.durationsMs});
  return timed;
}

std::vector<TimedFrame> timedFrames(const ReplayResult& result) {
  std::vector<TimedFrame> frames;
  for (const auto& f : result.frames) frames.push_back(timedFrame(f));
  return frames;
}

std::vector<std::pair<std::string, std::vector<double>>> countsByPass(const ReplayResult& result, CostMeasure measure) {
  std::vector<std::pair<std::string, std::vector<double>>> passes;
  for (const auto& frame : result.frames)
    for (const auto& p : frame.passes) {
      auto it = std::find_if(passes.begin(), passes.end(), [&](const auto& e) { return e.first == p.name; });
      if (it == passes.end()) it = passes.insert(passes.end(), {p.name, {}});
      it->second.push_back(costOf(measure, p.counts));
    }
  return passes;
}

References capturedReferences(const Capture& capture, int begin, int end) {
  References references;
  for (int i = begin; i < end; ++i)
    if (auto r = loadReference(capture, i)) references.frames[i] = std::move(*r);
  return references;
}

References completeReferences(VulkanContext& vk, const Capture& capture, int begin, int end,
                              const std::vector<std::string>& assignments) {
  if (everyFrameReferenced(capture, begin, end)) return capturedReferences(capture, begin, end);
  References references{kScreenSpaceReference, {}};
  const Technique& reference = referenceTechnique();
  std::vector<std::string> own;
  for (const auto& a : assignments)
    if (reference.parameter(a.substr(0, a.find('=')))) own.push_back(a);
  ReplayOptions options(resolveSettings(reference, capture, "", own));
  options.frameBegin = begin;
  options.frameEnd = end;
  fmt::print(stderr, "the capture has no ray-traced reference: computing the screen-space reference\n");
  replayCapture(vk, capture, options, [&](const FrameOutput& f) { references.frames[f.index] = f.visibility; });
  return references;
}

RunResults runCapture(VulkanContext& vk, const Capture& capture, const RunRequest& request, const FrameSink& sink) {
  const ReplayOptions& options = request.replay;
  auto noHistory = request.temporal ? replayWithoutHistory(vk, capture, options) : std::map<int, std::vector<float>>{};
  float blendWeight = blendWeightOf(options.settings);
  RunResults results{{}, RunAnalysis(request.references ? request.references->kind : kRayTracedReference, request.flip,
                                     request.temporal)};
  results.replay = replayCapture(vk, capture, options, [&](const FrameOutput& frame) {
    std::optional<std::vector<float>> loaded;
    AnalyzedFrame analyzed = analyzedFrame(capture, frame, referenceOf(capture, request.references, frame.index, loaded));
    analyzed.historyWeight = blendWeight;
    if (auto it = noHistory.find(frame.index); it != noHistory.end()) analyzed.noHistory = it->second.data();
    results.analysis.addFrame(analyzed);
    if (sink) sink(frame);
  });
  return results;
}

}  // namespace aor
