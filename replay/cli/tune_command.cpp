// `aoreplay tune`: fits a technique's constants to the captures' ray-traced references
// (docs/tuning.md). Every candidate is a real replay of every training capture; the search is in
// tune/tuner.h, the outputs in report/tune_report.h.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>

#include <fmt/format.h>

#include "cli/commands.h"
#include "cli/handlers.h"
#include "capture/library.h"
#include "cli/number_options.h"
#include "core/output_directory.h"
#include "report/run_outputs.h"
#include "report/tune_report.h"
#include "techniques/registry.h"
#include "techniques/settings_file.h"
#include "tune/cross_validation.h"
#include "tune/tuning.h"
#include "vk/context.h"

namespace aor::cli {
namespace {

namespace fs = std::filesystem;

struct TuneArgs {
  std::vector<std::string> captures, holdout;
  TuneRequest request{defaultTechnique().name};
  TuneLimits limits;
  std::string out, device;
  bool crossValidate = false;
  double margin = kDefaultCrossValidationMargin;
};

std::string valuesText(const std::vector<TuneDimension>& dims, const std::vector<double>& values) {
  std::string out;
  for (size_t i = 0; i < dims.size(); ++i) out += fmt::format("{}{}={:.4g}", i ? " " : "", dims[i].name, values[i]);
  return out;
}

// "[12/40] rmse 0.08123, best 0.07901 (radius_scale=1.41 power=2.05), about 35 s left"; the time
// left is of the search under way: `started` is reset as each (cross-validation fold's) search begins.
auto progressPrinter(const std::string& objective, const std::vector<TuneDimension>& dims,
                     std::shared_ptr<std::chrono::steady_clock::time_point> started) {
  return [=](const std::vector<TuneEvaluation>& done, int best, int max) {
    double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - *started).count();
    double left = elapsed / double(done.size()) * double(max - int(done.size()));
    std::string bestText = best < 0 ? "none within the budget yet"
                                    : fmt::format("{:.5f} ({})", done[size_t(best)].measure.objective, valuesText(dims, done[size_t(best)].values));
    fmt::print(stderr, "[{}/{}] {} {:.5f}, best {}, at most {:.0f} s left\n", done.size(), max, objective,
               done.back().measure.objective, bestText, left);
  };
}

// --cv: the folds, each a whole tuning, with a line as each starts.
std::optional<CrossValidation> crossValidateIfAsked(const TuneArgs& args, VulkanContext& vk, const TuneLimits& limits,
                                                   const std::vector<TuneCapture>& training,
                                                   const std::shared_ptr<std::chrono::steady_clock::time_point>& searchStart) {
  if (!args.crossValidate) return std::nullopt;
  auto started = [searchStart](size_t i, size_t n) {
    fmt::print(stderr, "cross-validation: fold {} of {}\n", i + 1, n);
    *searchStart = std::chrono::steady_clock::now();
  };
  auto cv = crossValidate(vk, args.request, limits, training, args.margin, started);
  fmt::print(stderr, "cross-validation: the fit on every capture\n");
  *searchStart = std::chrono::steady_clock::now();
  return cv;
}

int tuneCommand(const TuneArgs& args) {
  const TuneRequest& request = args.request;
  const Technique& technique = findTechnique(request.technique);
  checkObjective(request.objective);
  std::vector<TuneCapture> training, holdout;
  std::vector<fs::path> inputs;
  for (const auto& c : captureFoldersOf(args.captures)) training.push_back(loadTuneCapture(c, request.frames));
  for (const auto& c : captureFoldersOf(args.holdout)) holdout.push_back(loadTuneCapture(c, request.frames));
  if (args.crossValidate) requireFolds(training.size());  // before any output folder or device
  for (const auto* list : {&training, &holdout})
    for (const auto& t : *list) inputs.push_back(t.capture.folder);
  TuneRun run = planTuning(request, args.limits, training, holdout);
  OutputDirectory out(args.out.empty() ? fs::path("out") / ("tune-" + technique.name) : fs::path(args.out), ResultKind::Tune, inputs);
  std::optional<CrossValidation> cv;
  {
    ContextScope context({args.device, false, optionalExtensionsOf({tuneStart(request, training.front().capture)})});
    TuneLimits limits = args.limits;
    auto searchStart = std::make_shared<std::chrono::steady_clock::time_point>(std::chrono::steady_clock::now());
    limits.progress = progressPrinter(request.objective, run.dimensions, searchStart);
    std::vector<std::string> names;
    for (const auto& d : run.dimensions) names.push_back(d.name);
    fmt::print(stderr, "tuning {} of {} on {} capture(s), at most {} evaluations\n", fmt::join(names, ", "), technique.name,
               training.size(), limits.maxEvaluations);
    cv = crossValidateIfAsked(args, context.vk, limits, training, searchStart);
    tuneSettings(context.vk, request, limits, training, holdout, run);
  }
  const bool refused = cv && !cv->accepted();
  nlohmann::json tuneDocument = tuneJson(run);
  if (cv) tuneDocument["cross_validation"] = crossValidationJson(*cv);
  writeJson(out.staging() / "tune.json", tuneDocument);
  writeJson(out.staging() / "tune_times.json", tuneTimesJson(run));
  writeJson(out.staging() / "tuned.settings.json", refused ? run.startSettingsFile : run.settingsFile);
  writeText(out.staging() / "tune_objective.svg", tuneObjectiveSvg(run));
  writeText(out.staging() / "tune_error_ms.svg", tuneErrorMsSvg(run));
  out.commit();

  const auto& best = run.search.evaluations[size_t(run.search.best)];
  fmt::print("tuned {} on {} ({} evaluations, device {}): {}\n", technique.name, fmt::join(run.training, ", "),
             run.search.evaluations.size(), run.device, valuesText(run.dimensions, best.values));
  fmt::print("{}", tuneSummary(run));
  if (cv) fmt::print("{}", crossValidationSummary(*cv, request.objective));
  fmt::print("outputs: {}/ (tune.json, tune_times.json, tuned.settings.json, tune_objective.svg, tune_error_ms.svg)\n",
             out.finalPath().string());
  return refused ? kExitFailed : kExitOk;
}

}  // namespace

void registerTuneCommand(CLI::App& app) {
  auto args = std::make_shared<TuneArgs>();
  auto* cmd = app.add_subcommand("tune", "fit a technique's constants to the captures' ray-traced references");
  cmd->add_option("captures", args->captures,
                  "training capture folders (each needs ray-traced references); a folder without capture.json is a "
                  "library: its capture subfolders")->required();
  cmd->add_option("--technique", args->request.technique, "technique whose keys are tuned")->capture_default_str();
  cmd->add_option("--keys", args->request.keys,
                  "comma-separated keys to search (default: those the technique marks tunable; `aoreplay techniques` "
                  "lists them); radius is searched as radius_scale, a factor in [0.25, 4] on each capture's scene.ao_radius");
  cmd->add_option("--objective", args->request.objective,
                  "rmse, mse, ssim (1 - SSIM) or flip (mean LDR-FLIP), mean over the training captures")
      ->capture_default_str();
  cmd->add_option("--budget-ms", args->limits.budgetMs,
                  "GPU ms per frame (median compute total): configurations over it are never chosen (times are "
                  "measured, so with a budget the result can differ run to run)")
      ->check(numberIn(1e-6, 1e9));
  cmd->add_option("--holdout", args->holdout, "capture folders scored before and after, never searched on");
  cmd->add_flag("--cv", args->crossValidate,
                "leave-one-capture-out cross-validation: each capture is scored by a fit on the others; the fit on all is "
                "recommended only when no fold got worse than the defaults by more than --cv-margin, else "
                "tuned.settings.json holds the defaults and tune exits 1");
  cmd->add_option("--cv-margin", args->margin,
                  "how much worse than the defaults a fold's held-out objective may get, as a fraction (0.02: +2 %)")
      ->check(numberIn(0.0, 10.0))->capture_default_str();
  cmd->add_option("--preset", args->request.preset, "the technique's preset to start from (default: its default)");
  cmd->add_option("--set", args->request.assignments, "KEY=VALUE held fixed, repeatable");
  cmd->add_option("--range", args->request.ranges, "KEY=MIN:MAX narrows a tuned key's declared range, repeatable");
  cmd->add_option("--frames", args->request.frames, "half-open frame range A:B of every capture (default: all)");
  cmd->add_option("--max-evaluations", args->limits.maxEvaluations, "configurations replayed, the untuned start included")
      ->check(wholeIn(1, 100000))->capture_default_str();
  cmd->add_option("--grid-points", args->limits.gridPoints, "grid points per key before the local search (fewer when the grid "
                  "would take over half the evaluations)")->check(wholeIn(1, 100))->capture_default_str();
  cmd->add_option("--repeat", args->request.repeat, "timed executions of each frame")->check(wholeIn(1, 1000))->capture_default_str();
  cmd->add_option("--warmup", args->request.warmup, "untimed executions of each frame first")->check(wholeIn(0, 1000))->capture_default_str();
  cmd->add_option("--out", args->out, "output folder (default out/tune-<technique>/)");
  cmd->add_option("--device", args->device, "Vulkan device: index or name substring (default lavapipe)");
  handlers()["tune"] = [args] { return tuneCommand(*args); };
}

}  // namespace aor::cli
