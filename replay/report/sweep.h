#pragma once
// `aoreplay sweep`: one row per configuration (GPU time next to error against the reference),
// Pareto flags, and the files it writes: sweep.json, sweep.csv, sweep.svg, plus the terminal table.
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "pipeline/settings.h"

namespace aor {

struct SweepConfig {
  std::string name;  // e.g. "high" or "high slices=4 thin=1"
  AoSettings settings;
};

struct SweepRow {
  SweepConfig config;
  std::vector<std::pair<std::string, double>> passMs;  // per live pass, median over frames x repeats
  double totalMs = 0;                                  // totalMedianMs (report/pipeline_time.h)
  nlohmann::json error;                                // ErrorAnalysis::summaryJson()
  double rmse = 0, ssim = 0;
  bool pareto = false;
};

// Presets x the cartesian product of the grid axes ("KEY=v1,v2,..."; KEY is a --set key or
// `technique`), each applied on top of `base` in that order. Throws InputError naming the bad axis.
std::vector<SweepConfig> expandSweep(const AoSettings& base, const std::vector<std::string>& presets,
                                     const std::vector<std::string>& grid);

// A row is Pareto-optimal when no other row is at least as fast and at least as accurate (RMSE)
// and strictly better in one of the two.
void markPareto(std::vector<SweepRow>& rows);

struct SweepInfo {
  std::string capture, device, referenceKind;  // referenceKind: "ray-traced" or "screen-space"
  int frameBegin = 0, frameEnd = 0, repeat = 1, warmup = 0;
};

nlohmann::json sweepJson(const SweepInfo& info, const std::vector<SweepRow>& rows);
std::string sweepCsv(const std::vector<SweepRow>& rows);
std::string sweepSvg(const SweepInfo& info, const std::vector<SweepRow>& rows);
std::string sweepTable(const std::vector<SweepRow>& rows);

}  // namespace aor
