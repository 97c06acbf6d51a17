// `aoreplay tune`: fits a technique's constants to the captures' ray-traced references (README,
// "Tuning"). Every candidate is a real replay of every training capture; the search is in
// tune/tuner.h, the outputs in report/tune_report.h.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <map>
#include <memory>

#include <fmt/format.h>

#include "cli/commands.h"
#include "cli/handlers.h"
#include "options/number.h"
#include "cli/number_options.h"
#include "cli/settings_options.h"
#include "metrics/error_metrics.h"
#include "replay_loop/analyzed_output.h"
#include "replay_loop/replayer.h"
#include "core/output_directory.h"
#include "report/gpu_total.h"
#include "report/run_outputs.h"
#include "report/tune_report.h"
#include "techniques/registry.h"
#include "techniques/settings_file.h"
#include "tune/tuner.h"
#include "vk/context.h"

namespace aor::cli {
namespace {

namespace fs = std::filesystem;

// The radius is searched as a factor on each capture's scene.ao_radius: captures differ in scale.
constexpr const char* kRadiusScale = "radius_scale";
constexpr double kRadiusScaleMin = 0.25, kRadiusScaleMax = 4.0;

struct TuneArgs {
  std::vector<std::string> captures, holdout;
  std::string technique = "gtao", preset, keys, objective = "rmse", frames, out, device;
  std::vector<std::string> assignments, ranges;
  double budgetMs = 0;
  int maxEvaluations = 40, gridPoints = 3, repeat = 1, warmup = 1;
};

struct TuneCapture {
  Capture capture;
  int begin = 0, end = 0;
  std::map<int, std::vector<float>> references;  // the frames scored
};

TuneCapture loadTuneCapture(const std::string& folder, const std::string& frames) {
  TuneCapture t{loadCapture(folder)};
  SettingsOptions range;
  range.frames = frames;
  std::tie(t.begin, t.end) = range.frameRange(t.capture);
  for (int i = t.begin; i < t.end; ++i)
    if (auto r = loadReference(t.capture, i)) t.references[i] = std::move(*r);
  if (t.references.empty())
    throw InputError((t.capture.folder / "capture.json").string(), std::nullopt, "frames[].reference",
                     fmt::format("no frame in {}:{} has a ray-traced reference, and tune fits to one (aoreplay capture "
                                 "writes them)", t.begin, t.end));
  return t;
}

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

// The recipe of one candidate: the fixed settings, then the searched values.
SettingsRecipe candidate(const TuneArgs& args, const std::vector<TuneDimension>& dims, const std::vector<double>& values) {
  SettingsRecipe recipe{args.technique, args.preset, args.assignments, 1.0};
  const Technique& technique = findTechnique(args.technique);
  for (size_t i = 0; i < dims.size(); ++i) {
    if (dims[i].name == kRadiusScale) recipe.radiusScale = values[i];
    else recipe.assignments.push_back(dims[i].name + "=" + valueText(*technique.parameter(dims[i].name), values[i]));
  }
  return recipe;
}

double objectiveOf(const std::string& objective, double rmse, double ssim, double flip) {
  if (objective == "mse") return rmse * rmse;
  if (objective == "ssim") return 1.0 - ssim;
  if (objective == "flip") return flip;
  return rmse;
}

CaptureScore scoreCapture(VulkanContext& vk, const TuneCapture& t, const SettingsRecipe& recipe, const TuneArgs& args) {
  ReplayOptions options(recipe.resolve(t.capture));
  options.frameBegin = t.begin;
  options.frameEnd = t.end;
  options.repeat = args.repeat;
  options.warmup = args.warmup;
  ErrorAnalysis errors("ray-traced", args.objective == "flip");
  auto result = replayCapture(vk, t.capture, options, [&](const FrameOutput& f) {
    auto ref = t.references.find(f.index);
    if (ref == t.references.end()) return;
    AnalyzedFrame frame = analyzedFrame(t.capture, f, &ref->second);
    errors.addFrame(frame);
  });
  auto summary = errors.summaryJson();
  CaptureScore s{t.capture.name, int(t.references.size()), summary["rmse"].get<double>(), 0, summary["ssim"].get<double>()};
  s.mse = s.rmse * s.rmse;
  s.flip = summary.value("flip", 0.0);
  s.objective = objectiveOf(args.objective, s.rmse, s.ssim, s.flip);
  s.ms = totalMedianMs(timedFrames(result));
  return s;
}

ConfigScore scoreAll(VulkanContext& vk, const std::vector<TuneCapture>& captures, const SettingsRecipe& recipe, const TuneArgs& args) {
  ConfigScore score;
  for (const auto& t : captures) score.captures.push_back(scoreCapture(vk, t, recipe, args));
  for (const auto& c : score.captures) {
    score.objective += c.objective / double(captures.size());
    score.ms += c.ms / double(captures.size());
  }
  return score;
}

std::string valuesText(const std::vector<TuneDimension>& dims, const std::vector<double>& values) {
  std::string out;
  for (size_t i = 0; i < dims.size(); ++i) out += fmt::format("{}{}={:.4g}", i ? " " : "", dims[i].name, values[i]);
  return out;
}

// "[12/40] rmse 0.08123, best 0.07901 (radius_scale=1.41 power=2.05), about 35 s left"
auto progressPrinter(const TuneArgs& args, const std::vector<TuneDimension>& dims) {
  auto started = std::chrono::steady_clock::now();
  return [=](const std::vector<TuneEvaluation>& done, int best, int max) {
    double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    double left = elapsed / double(done.size()) * double(max - int(done.size()));
    std::string bestText = best < 0 ? "none within the budget yet"
                                    : fmt::format("{:.5f} ({})", done[size_t(best)].measure.objective, valuesText(dims, done[size_t(best)].values));
    fmt::print(stderr, "[{}/{}] {} {:.5f}, best {}, at most {:.0f} s left\n", done.size(), max, args.objective,
               done.back().measure.objective, bestText, left);
  };
}

int tuneCommand(const TuneArgs& args) {
  const Technique& technique = findTechnique(args.technique);
  if (args.objective != "rmse" && args.objective != "mse" && args.objective != "ssim" && args.objective != "flip")
    throw InputError("", std::nullopt, "--objective", fmt::format("'{}' is not rmse, mse, ssim or flip", args.objective));
  std::vector<TuneCapture> training, holdout;
  std::vector<fs::path> inputs;
  for (const auto& c : args.captures) training.push_back(loadTuneCapture(c, args.frames));
  for (const auto& c : args.holdout) holdout.push_back(loadTuneCapture(c, args.frames));
  for (const auto* list : {&training, &holdout})
    for (const auto& t : *list) inputs.push_back(t.capture.folder);

  TuneRun run{technique.name, args.preset, args.objective, "", args.assignments};
  auto keys = chosenKeys(technique, args.keys);
  for (const Parameter* p : keys)
    for (const auto& a : args.assignments)
      if (a.rfind(p->key + "=", 0) == 0)
        throw InputError("", std::nullopt, "--set", fmt::format("{} is both fixed by --set and tuned by --keys", p->key));
  Settings start = SettingsRecipe{args.technique, args.preset, args.assignments, 1.0}.resolve(training.front().capture);
  run.dimensions = dimensionsOf(keys, start, args.ranges);
  for (const auto& t : training) run.training.push_back(t.capture.name);
  for (const auto& t : holdout) run.holdout.push_back(t.capture.name);
  run.frames = args.frames;
  run.budgetMs = args.budgetMs;
  OutputDirectory out(args.out.empty() ? fs::path("out") / ("tune-" + technique.name) : fs::path(args.out), ResultKind::Tune, inputs);

  {
    ContextScope context({args.device, false, optionalExtensionsOf({start})});
    run.device = context.vk.info.name;
    TuneProblem problem;
    problem.dimensions = run.dimensions;
    problem.maxEvaluations = args.maxEvaluations;
    problem.gridPoints = args.gridPoints;
    if (args.budgetMs > 0) problem.budget = args.budgetMs;
    problem.evaluate = [&](const std::vector<double>& values) {
      run.trainingScores.push_back(scoreAll(context.vk, training, candidate(args, run.dimensions, values), args));
      return TuneMeasure{run.trainingScores.back().objective, run.trainingScores.back().ms};
    };
    problem.progress = progressPrinter(args, run.dimensions);
    std::vector<std::string> names;
    for (const auto& d : run.dimensions) names.push_back(d.name);
    fmt::print(stderr, "tuning {} of {} on {} capture(s), at most {} evaluations\n", fmt::join(names, ", "), technique.name,
               training.size(), args.maxEvaluations);
    run.search = tune(problem);
    if (run.search.best < 0) {
      double fastest = 1e300;
      for (const auto& s : run.trainingScores) fastest = std::min(fastest, s.ms);
      throw InputError("", std::nullopt, "--budget-ms", fmt::format("no evaluated configuration ran within {} ms (the fastest took {:.3f} ms)", args.budgetMs, fastest));
    }
    run.trainingBefore = run.trainingScores.front();
    run.trainingAfter = run.trainingScores[size_t(run.search.best)];
    SettingsRecipe best = candidate(args, run.dimensions, run.search.evaluations[size_t(run.search.best)].values);
    if (!holdout.empty()) {
      run.holdoutBefore = scoreAll(context.vk, holdout, candidate(args, run.dimensions, run.search.evaluations.front().values), args);
      run.holdoutAfter = scoreAll(context.vk, holdout, best, args);
    }
    run.settingsFile = settingsFileJson(best);
  }
  writeJson(out.staging() / "tune.json", tuneJson(run));
  writeJson(out.staging() / "tune_times.json", tuneTimesJson(run));
  writeJson(out.staging() / "tuned.settings.json", run.settingsFile);
  writeText(out.staging() / "tune_objective.svg", tuneObjectiveSvg(run));
  writeText(out.staging() / "tune_error_ms.svg", tuneErrorMsSvg(run));
  out.commit();

  const auto& best = run.search.evaluations[size_t(run.search.best)];
  fmt::print("tuned {} on {} ({} evaluations, device {}): {}\n", technique.name, fmt::join(run.training, ", "),
             run.search.evaluations.size(), run.device, valuesText(run.dimensions, best.values));
  fmt::print("{}", tuneSummary(run));
  fmt::print("outputs: {}/ (tune.json, tune_times.json, tuned.settings.json, tune_objective.svg, tune_error_ms.svg)\n",
             out.finalPath().string());
  return kExitOk;
}

}  // namespace

void registerTuneCommand(CLI::App& app) {
  auto args = std::make_shared<TuneArgs>();
  auto* cmd = app.add_subcommand("tune", "fit a technique's constants to the captures' ray-traced references");
  cmd->add_option("captures", args->captures, "training capture folders (each needs ray-traced references)")->required();
  cmd->add_option("--technique", args->technique, "technique whose keys are tuned")->capture_default_str();
  cmd->add_option("--keys", args->keys,
                  "comma-separated keys to search (default: those the technique marks tunable; `aoreplay techniques` "
                  "lists them); radius is searched as radius_scale, a factor in [0.25, 4] on each capture's scene.ao_radius");
  cmd->add_option("--objective", args->objective,
                  "rmse, mse, ssim (1 - SSIM) or flip (mean LDR-FLIP), mean over the training captures")
      ->capture_default_str();
  cmd->add_option("--budget-ms", args->budgetMs,
                  "GPU ms per frame (median compute total): configurations over it are never chosen (times are "
                  "measured, so with a budget the result can differ run to run)")
      ->check(numberIn(1e-6, 1e9));
  cmd->add_option("--holdout", args->holdout, "capture folders scored before and after, never searched on");
  cmd->add_option("--preset", args->preset, "the technique's preset to start from (default: its default)");
  cmd->add_option("--set", args->assignments, "KEY=VALUE held fixed, repeatable");
  cmd->add_option("--range", args->ranges, "KEY=MIN:MAX narrows a tuned key's declared range, repeatable");
  cmd->add_option("--frames", args->frames, "half-open frame range A:B of every capture (default: all)");
  cmd->add_option("--max-evaluations", args->maxEvaluations, "configurations replayed, the untuned start included")
      ->check(wholeIn(1, 100000))->capture_default_str();
  cmd->add_option("--grid-points", args->gridPoints, "grid points per key before the local search (fewer when the grid "
                  "would take over half the evaluations)")->check(wholeIn(1, 100))->capture_default_str();
  cmd->add_option("--repeat", args->repeat, "timed executions of each frame")->check(wholeIn(1, 1000))->capture_default_str();
  cmd->add_option("--warmup", args->warmup, "untimed executions of each frame first")->check(wholeIn(0, 1000))->capture_default_str();
  cmd->add_option("--out", args->out, "output folder (default out/tune-<technique>/)");
  cmd->add_option("--device", args->device, "Vulkan device: index or name substring (default lavapipe)");
  handlers()["tune"] = [args] { return tuneCommand(*args); };
}

}  // namespace aor::cli
