#pragma once
// `aoreplay sweep`: one row per configuration (GPU time next to error against the reference),
// Pareto flags, and the files it writes: sweep.json, sweep.csv, sweep.svg, plus the terminal table.
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include <functional>

#include "run/run.h"
#include "technique_api/settings.h"
#include "techniques/registry.h"

namespace aor {

struct SweepConfig {
  std::string name;  // e.g. "high", "high slices=4 thin=1", "high technique=xegtao"
  Settings settings;
};

// A grid past this many configurations (a run each) is refused unless --max-configurations allows
// it: 10 values on each of 6 keys is 10^6 runs, about 10 hours on lavapipe.
inline constexpr size_t kDefaultMaxConfigurations = 1000;

struct SweepRequest {
  std::vector<std::string> presets;      // empty: every preset of each technique
  std::vector<std::string> grid;         // "KEY=v1,v2,...": a technique's key, or `technique`
  std::vector<std::string> assignments;  // --set KEY=VALUE, before the grid
  std::string defaultTechnique = aor::defaultTechnique().name;  // without a technique axis
  size_t maxConfigurations = kDefaultMaxConfigurations;
};
struct SweepPlan {
  std::vector<SweepConfig> configs;
  std::vector<std::string> notes;  // presets skipped for techniques that lack them
};
// Settings of `technique` with `preset` ("" for its default) and the assignments it declares.
using SettingsResolver =
    std::function<Settings(const Technique& technique, std::string_view preset, const std::vector<std::string>& assignments)>;

// Each technique (the `technique` axis, else the default) runs each of its presets named in
// `presets` (a preset it lacks is skipped with a note; a technique without presets runs once), times
// the cartesian product of the other grid axes. A --set or grid key applies to every technique that
// declares it and is an error only if none does. Throws InputError naming the bad axis or key, or
// when the plan has more than `maxConfigurations` configurations (counted before any is made).
SweepPlan expandSweep(const SweepRequest& request, const SettingsResolver& resolve);

struct SweepRow {
  SweepConfig config;
  // With counted cost (measure "instructions" or "cycles") passMs and totalMs hold counts over the
  // frames: each pass's sum, and the compute passes' sum.
  std::string measure = "time";
  std::vector<std::pair<std::string, double>> passMs;  // per live pass, median over frames x repeats
  double totalMs = 0;                                  // totalMedianMs (run/gpu_total.h)
  nlohmann::json error;                                // ErrorAnalysis::summaryJson()
  double rmse = 0, ssim = 0;
  double haloRmse = 0, haloBias = 0;  // over the halo band (error.halo_band; 0 pixels: both 0)
  int64_t haloPixels = 0;
  bool pareto = false;
  // Techniques that accumulate samples over frames (Technique::samplesValue): the samples per pixel
  // its frames reached, least and most; 0 for the others.
  double sppMin = 0, sppMax = 0;
  std::string samplesLabel() const;  // "4-64 spp", or "" for a technique without them
};

// A configuration's row from its run (error against the sweep's references, no temporal metrics).
SweepRow sweepRow(const SweepConfig& config, const RunResults& results);

// The error a sweep ranks and plots by: RMSE over every surface pixel, or over the halo band only.
enum class SweepRank { Rmse, HaloBand };
const char* sweepRankName(SweepRank rank);   // "rmse", "halo_band"
double rankedError(const SweepRow& row, SweepRank rank);

// A row is Pareto-optimal when no other row is at least as fast and at least as accurate (the
// ranked error) and strictly better in one of the two.
void markPareto(std::vector<SweepRow>& rows, SweepRank rank = SweepRank::Rmse);

struct SweepInfo {
  std::string capture, device, referenceKind;  // referenceKind: "ray-traced" or "screen-space"
  std::string measure = "time";                // or a counted one: "instructions", "cycles"
  int frameBegin = 0, frameEnd = 0, repeat = 1, warmup = 0;
  SweepRank rank = SweepRank::Rmse;
};

nlohmann::json sweepJson(const SweepInfo& info, const std::vector<SweepRow>& rows);
std::string sweepCsv(const std::vector<SweepRow>& rows);
std::string sweepSvg(const SweepInfo& info, const std::vector<SweepRow>& rows);
// The terminal's tables: with one technique, a row per configuration with its passes; with
// several, a totals table (numbered configurations: time, errors, Pareto) and then, per
// technique, its passes against its configurations' numbers only, in blocks no wider than 120
// characters, so no table carries another technique's columns.
std::string sweepTable(const std::vector<SweepRow>& rows);

// The techniques of the rows, in first-seen order.
std::vector<std::string> sweepTechniques(const std::vector<SweepRow>& rows);

// Every pass name of the rows, in first-seen order (the table's and the page's columns).
std::vector<std::string> sweepPassNames(const std::vector<SweepRow>& rows);

}  // namespace aor
