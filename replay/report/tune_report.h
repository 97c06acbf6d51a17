#pragma once
// What `aoreplay tune` writes (README, "Tuning"): tune.json, every error figure and the search,
// bit-identical for the same inputs on the same device; tune_times.json, the GPU times, which are
// measurements and differ run to run; and two plots.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tune/tuner.h"

namespace aor {

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
};

nlohmann::json tuneJson(const TuneRun& run);
nlohmann::json tuneTimesJson(const TuneRun& run);
std::string tuneObjectiveSvg(const TuneRun& run);  // objective per evaluation and the best so far
std::string tuneErrorMsSvg(const TuneRun& run);    // every evaluation; before and after per capture
// The terminal's summary: objective before and after, training and hold-out, per capture.
std::string tuneSummary(const TuneRun& run);

}  // namespace aor
