#include "tune/tuning.h"

#include <algorithm>

#include <fmt/format.h>

#include "core/input_error.h"
#include "options/frame_range.h"
#include "options/number.h"
#include "run/gpu_total.h"
#include "techniques/registry.h"
#include "vk/context.h"

namespace aor {
namespace {

// The radius is searched as a factor on each capture's scene.ao_radius: captures differ in scale.
constexpr const char* kRadiusScale = "radius_scale";
constexpr double kRadiusScaleMin = 0.25, kRadiusScaleMax = 4.0;

// The keys to search: --keys, else every key the technique marks tunable. Unknown keys and keys
// that are not tunable (flags, enums, sample counts) are refused.
std::vector<const Parameter*> chosenKeys(const Technique& technique, const std::string& keys) {
  std::vector<const Parameter*> out;
  if (keys.empty()) {
    for (const auto& p : technique.parameters)
      if (p.tunable) out.push_back(&p);
  } else {
    for (size_t start = 0; start <= keys.size();) {
      size_t comma = std::min(keys.find(',', start), keys.size());
      std::string key = keys.substr(start, comma - start);
      const Parameter* p = technique.parameter(key);
      if (!p)
        throw InputError("", std::nullopt, "--keys", fmt::format("technique {} has no key '{}' (its keys: {})", technique.name, key, technique.keyList()));
      if (!p->tunable)
        throw InputError("", std::nullopt, "--keys", fmt::format("key '{}' of {} is not tunable (tunable: {})", key, technique.name, technique.tunableKeyList()));
      if (std::find(out.begin(), out.end(), p) != out.end())
        throw InputError("", std::nullopt, "--keys", fmt::format("key '{}' is named twice", key));
      out.push_back(p);
      start = comma + 1;
    }
  }
  if (out.empty()) throw InputError("", std::nullopt, "--keys", fmt::format("technique {} has no tunable keys", technique.name));
  return out;
}

// --range KEY=MIN:MAX narrows a key's declared range.
std::map<std::string, std::pair<double, double>> parseRanges(const std::vector<std::string>& ranges) {
  std::map<std::string, std::pair<double, double>> out;
  for (const auto& r : ranges) {
    auto eq = r.find('='), colon = r.find(':', eq == std::string::npos ? 0 : eq);
    auto bad = [&] { return InputError("", std::nullopt, "--range", fmt::format("'{}' is not KEY=MIN:MAX with MIN <= MAX", r)); };
    if (eq == std::string::npos || eq == 0 || colon == std::string::npos) throw bad();
    // Each bound the whole text between its separators, finite (options/number.h): "1:2:3" is refused.
    double lo = 0, hi = 0;
    try {
      lo = parseNumber(std::string_view(r).substr(eq + 1, colon - eq - 1), "--range", -1e30, 1e30);
      hi = parseNumber(std::string_view(r).substr(colon + 1), "--range", -1e30, 1e30);
    } catch (const InputError&) {
      throw bad();
    }
    if (!(lo <= hi)) throw bad();
    if (!out.emplace(r.substr(0, eq), std::make_pair(lo, hi)).second)
      throw InputError("", std::nullopt, "--range", fmt::format("key '{}' is given twice", r.substr(0, eq)));
  }
  return out;
}

std::vector<TuneDimension> dimensionsOf(const std::vector<const Parameter*>& keys, const Settings& start,
                                        const std::vector<std::string>& ranges) {
  auto narrowed = parseRanges(ranges);
  std::vector<TuneDimension> dims;
  for (const Parameter* p : keys) {
    TuneDimension d{p->key, p->min, p->max, p->type == ParameterType::Int, p->type == ParameterType::Float, start.value(p->key)};
    if (p->key == kRadiusKey) d = {kRadiusScale, kRadiusScaleMin, kRadiusScaleMax, false, false, 1.0};
    if (auto it = narrowed.find(d.name); it != narrowed.end()) {
      if (it->second.first < d.min || it->second.second > d.max)
        throw InputError("", std::nullopt, "--range", fmt::format("{}: [{}, {}] leaves the declared range [{}, {}]", d.name, it->second.first, it->second.second, d.min, d.max));
      std::tie(d.min, d.max) = it->second;
      d.start = std::clamp(d.start, d.min, d.max);
      narrowed.erase(it);
    }
    dims.push_back(d);
  }
  if (!narrowed.empty())
    throw InputError("", std::nullopt, "--range", fmt::format("'{}' is not a key being tuned", narrowed.begin()->first));
  return dims;
}

double objectiveOf(const std::string& objective, double rmse, double ssim, double flip) {
  if (objective == "mse") return rmse * rmse;
  if (objective == "ssim") return 1.0 - ssim;
  if (objective == "flip") return flip;
  return rmse;
}

CaptureScore scoreCapture(VulkanContext& vk, const TuneCapture& t, const SettingsRecipe& recipe, const TuneRequest& request) {
  RunRequest run(ReplayOptions(recipe.resolve(t.capture)));
  run.replay.frameBegin = t.begin;
  run.replay.frameEnd = t.end;
  run.replay.repeat = request.repeat;
  run.replay.warmup = request.warmup;
  run.references = &t.references;
  run.temporal = false;
  run.flip = request.objective == "flip";
  RunResults results = runCapture(vk, t.capture, run);
  auto summary = results.analysis.summaryJson()["error"];
  CaptureScore s{t.capture.name, int(t.references.frames.size()), summary["rmse"].get<double>(), 0, summary["ssim"].get<double>()};
  s.mse = s.rmse * s.rmse;
  s.flip = summary.value("flip", 0.0);
  s.objective = objectiveOf(request.objective, s.rmse, s.ssim, s.flip);
  s.ms = totalMedianMs(timedFrames(results.replay));
  return s;
}

}  // namespace

TuneCapture loadTuneCapture(const std::string& folder, const std::string& frames) {
  TuneCapture t{loadCapture(folder)};
  std::tie(t.begin, t.end) = frameRange(t.capture, frames);
  t.references = capturedReferences(t.capture, t.begin, t.end);
  if (t.references.frames.empty())
    throw InputError((t.capture.folder / "capture.json").string(), std::nullopt, "frames[].reference",
                     fmt::format("no frame in {}:{} has a ray-traced reference, and tune fits to one (aoreplay capture "
                                 "writes them)", t.begin, t.end));
  return t;
}

void checkObjective(const std::string& objective) {
  if (objective != "rmse" && objective != "mse" && objective != "ssim" && objective != "flip")
    throw InputError("", std::nullopt, "--objective", fmt::format("'{}' is not rmse, mse, ssim or flip", objective));
}

std::vector<TuneDimension> tuneDimensions(const TuneRequest& request, const Settings& start) {
  auto keys = chosenKeys(start.technique(), request.keys);
  for (const Parameter* p : keys)
    for (const auto& a : request.assignments)
      if (a.rfind(p->key + "=", 0) == 0)
        throw InputError("", std::nullopt, "--set", fmt::format("{} is both fixed by --set and tuned by --keys", p->key));
  return dimensionsOf(keys, start, request.ranges);
}

SettingsRecipe tuneCandidate(const TuneRequest& request, const std::vector<TuneDimension>& dims, const std::vector<double>& values) {
  SettingsRecipe recipe{request.technique, request.preset, request.assignments, 1.0};
  const Technique& technique = findTechnique(request.technique);
  for (size_t i = 0; i < dims.size(); ++i) {
    if (dims[i].name == kRadiusScale) recipe.radiusScale = values[i];
    else recipe.assignments.push_back(dims[i].name + "=" + valueText(*technique.parameter(dims[i].name), values[i]));
  }
  return recipe;
}

ConfigScore scoreConfiguration(VulkanContext& vk, const std::vector<TuneCapture>& captures, const SettingsRecipe& recipe,
                               const TuneRequest& request) {
  ConfigScore score;
  for (const auto& t : captures) score.captures.push_back(scoreCapture(vk, t, recipe, request));
  for (const auto& c : score.captures) {
    score.objective += c.objective / double(captures.size());
    score.ms += c.ms / double(captures.size());
  }
  return score;
}

Settings tuneStart(const TuneRequest& request, const Capture& capture) {
  return SettingsRecipe{request.technique, request.preset, request.assignments, 1.0}.resolve(capture);
}

TuneRun planTuning(const TuneRequest& request, const TuneLimits& limits, const std::vector<TuneCapture>& training,
                     const std::vector<TuneCapture>& holdout) {
  TuneRun run{request.technique, request.preset, request.objective, "", request.assignments};
  run.dimensions = tuneDimensions(request, tuneStart(request, training.front().capture));
  for (const auto& t : training) run.training.push_back(t.capture.name);
  for (const auto& t : holdout) run.holdout.push_back(t.capture.name);
  run.frames = request.frames;
  run.budgetMs = limits.budgetMs;
  return run;
}

namespace {

void refuseOverBudget(const TuneRun& run) {
  double fastest = 1e300;
  for (const auto& s : run.trainingScores) fastest = std::min(fastest, s.ms);
  throw InputError("", std::nullopt, "--budget-ms",
                   fmt::format("no evaluated configuration ran within {} ms (the fastest took {:.3f} ms)", run.budgetMs, fastest));
}

}  // namespace

void tuneSettings(VulkanContext& vk, const TuneRequest& request, const TuneLimits& limits,
                  const std::vector<TuneCapture>& training, const std::vector<TuneCapture>& holdout, TuneRun& run) {
  run.device = vk.info.name;
  TuneProblem problem;
  problem.dimensions = run.dimensions;
  problem.maxEvaluations = limits.maxEvaluations;
  problem.gridPoints = limits.gridPoints;
  if (limits.budgetMs > 0) problem.budget = limits.budgetMs;
  problem.evaluate = [&](const std::vector<double>& values) {
    run.trainingScores.push_back(scoreConfiguration(vk, training, tuneCandidate(request, run.dimensions, values), request));
    return TuneMeasure{run.trainingScores.back().objective, run.trainingScores.back().ms};
  };
  problem.progress = limits.progress;
  run.search = tune(problem);
  if (run.search.best < 0) refuseOverBudget(run);
  run.trainingBefore = run.trainingScores.front();
  run.trainingAfter = run.trainingScores[size_t(run.search.best)];
  SettingsRecipe best = tuneCandidate(request, run.dimensions, run.search.evaluations[size_t(run.search.best)].values);
  if (!holdout.empty()) {
    SettingsRecipe start = tuneCandidate(request, run.dimensions, run.search.evaluations.front().values);
    run.holdoutBefore = scoreConfiguration(vk, holdout, start, request);
    run.holdoutAfter = scoreConfiguration(vk, holdout, best, request);
  }
  run.settingsFile = settingsFileJson(best);
  run.startSettingsFile = settingsFileJson(tuneCandidate(request, run.dimensions, run.search.evaluations.front().values));
}

}  // namespace aor
