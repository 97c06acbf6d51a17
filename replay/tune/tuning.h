#pragma once
// The tuning problem behind `aoreplay tune`: which keys are searched over which box, each
// candidate's settings, and its score (real replays of every capture, error against the captures'
// ray-traced references). tuner.h searches; report/tune_report.h writes what a tuning found.
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "capture/capture.h"
#include "run/run.h"
#include "techniques/settings_file.h"
#include "tune/tuner.h"

namespace aor {

// What `aoreplay tune` was asked.
struct TuneRequest {
  std::string technique, preset, keys, objective = "rmse", frames;
  std::vector<std::string> assignments, ranges;
  int repeat = 1, warmup = 1;
};

// One capture replayed under one configuration.
struct CaptureScore {
  std::string capture;
  int frames = 0;         // frames with a reference, scored
  double rmse = 0, mse = 0, ssim = 0;
  double flip = 0;        // mean LDR-FLIP; only computed for --objective flip
  double objective = 0;   // of the run's --objective
  double ms = 0;          // median compute total per frame
};

struct ConfigScore {
  std::vector<CaptureScore> captures;
  double objective = 0;  // mean over the captures
  double ms = 0;         // mean over the captures
};

struct TuneRun {
  std::string technique, preset, objective, device;
  std::vector<std::string> assignments;   // fixed --set values
  std::vector<TuneDimension> dimensions;  // radius appears as radius_scale
  std::vector<std::string> training, holdout;
  std::string frames;                     // --frames as given, empty for all
  double budgetMs = 0;                    // 0: none
  TuneResult search;
  std::vector<ConfigScore> trainingScores;  // one per evaluation, in order
  ConfigScore trainingBefore, trainingAfter, holdoutBefore, holdoutAfter;
  nlohmann::json settingsFile;            // what tuned.settings.json holds
  nlohmann::json startSettingsFile;       // the same for the untuned start (the defaults and --set)
};

// A capture to train or score on: its frames in --frames, and those frames' references.
struct TuneCapture {
  Capture capture;
  int begin = 0, end = 0;
  References references;
};
// Throws InputError when no frame in the range has a ray-traced reference.
TuneCapture loadTuneCapture(const std::string& folder, const std::string& frames);

// Refuses an objective other than rmse, mse, ssim and flip (InputError, --objective).
void checkObjective(const std::string& objective);
// The box searched: --keys (else the keys the technique marks tunable), each over its declared
// range narrowed by --range, starting at the value `start` holds; the radius as a factor on each
// capture's scene.ao_radius (radius_scale). Throws InputError for unknown, untunable, repeated or
// --set-fixed keys and for ranges outside the declared ones.
std::vector<TuneDimension> tuneDimensions(const TuneRequest& request, const Settings& start);
// The recipe of one candidate: the fixed settings, then the searched values.
SettingsRecipe tuneCandidate(const TuneRequest& request, const std::vector<TuneDimension>& dimensions,
                             const std::vector<double>& values);
// Every capture replayed under `recipe`; the objective and time are means over the captures.
ConfigScore scoreConfiguration(VulkanContext& vk, const std::vector<TuneCapture>& captures, const SettingsRecipe& recipe,
                               const TuneRequest& request);

// The untuned settings on `capture`: the technique, its preset and the fixed --set values.
Settings tuneStart(const TuneRequest& request, const Capture& capture);

// How long the search may go on.
struct TuneLimits {
  int maxEvaluations = 40;
  int gridPoints = 3;
  double budgetMs = 0;  // 0: none
  std::function<void(const std::vector<TuneEvaluation>& done, int best, int max)> progress;
};
// What will be searched, checked before any device work: the run's description and its box.
// `training` holds at least one capture. Throws InputError as tuneDimensions does.
TuneRun planTuning(const TuneRequest& request, const TuneLimits& limits, const std::vector<TuneCapture>& training,
                   const std::vector<TuneCapture>& holdout);
// Searches the planned box on `training`, then scores the untuned and the best settings on
// `holdout`, filling `run`. Throws InputError (--budget-ms) when no configuration ran within the budget.
void tuneSettings(VulkanContext& vk, const TuneRequest& request, const TuneLimits& limits,
                  const std::vector<TuneCapture>& training, const std::vector<TuneCapture>& holdout, TuneRun& run);

}  // namespace aor
