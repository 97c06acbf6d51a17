#include "report/sweep.h"

#include <algorithm>
#include <numeric>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/input_error.h"
#include "core/pass_names.h"
#include "core/stats.h"
#include "report/run_outputs.h"
#include "report/svg_plot.h"
#include "techniques/registry.h"

namespace aor {
namespace {

struct GridAxis {
  std::string key;
  std::vector<std::string> values;
};

std::vector<std::string> splitList(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  for (std::string part; std::getline(in, part, ',');) parts.push_back(part);
  return parts;
}

GridAxis parseAxis(const std::string& text) {
  auto eq = text.find('=');
  GridAxis axis;
  if (eq != std::string::npos) {
    axis.key = text.substr(0, eq);
    axis.values = splitList(text.substr(eq + 1));
  }
  bool emptyValue = std::any_of(axis.values.begin(), axis.values.end(), [](const auto& v) { return v.empty(); });
  if (axis.key.empty() || axis.values.empty() || emptyValue)
    throw InputError("", std::nullopt, "--grid", fmt::format("'{}' is not KEY=v1,v2,...", text));
  return axis;
}



bool counted(const SweepRow& row) { return row.measure != "time"; }
// What a cost column is called after: "ms", or the counted measure.
std::string unitOf(const SweepRow& row) { return counted(row) ? row.measure : "ms"; }
std::string costText(const SweepRow& row, double value, size_t width) {
  return counted(row) ? fmt::format("{:>{}.0f}", value, width) : fmt::format("{:>{}.3f}", value, width);
}

double passMs(const SweepRow& row, const std::string& name) {
  for (const auto& [n, ms] : row.passMs)
    if (n == name) return ms;
  return 0;
}

std::string csvField(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

// The presets `t` runs: all of its own, or those of `request.presets` it has (others noted); "" for
// a technique without presets (it runs once, with its defaults).
std::vector<std::string> sweptPresets(const Technique& t, const SweepRequest& request, std::vector<std::string>& notes) {
  if (t.presets.empty()) return {""};
  std::vector<std::string> presets;
  if (request.presets.empty()) {
    for (const auto& p : t.presets) presets.push_back(p.name);
    return presets;
  }
  for (const auto& p : request.presets) {
    if (t.preset(p)) presets.push_back(p);
    else notes.push_back(fmt::format("technique {} has no preset '{}' (presets: {}): skipped", t.name, p, t.presetList()));
  }
  return presets;
}

}  // namespace

SweepPlan expandSweep(const SweepRequest& request, const SettingsResolver& resolve) {
  std::vector<GridAxis> axes;
  std::vector<const Technique*> techniques;
  bool techniqueAxis = false;
  for (const auto& g : request.grid) {
    GridAxis axis = parseAxis(g);
    const bool repeated = axis.key == "technique" ? techniqueAxis
                                                  : std::any_of(axes.begin(), axes.end(), [&](const GridAxis& a) { return a.key == axis.key; });
    if (repeated)
      throw InputError("", std::nullopt, "--grid", fmt::format("'{}' is a second axis of key '{}': give its values once, "
                                                             "comma-separated", g, axis.key));
    if (axis.key != "technique") {
      axes.push_back(axis);
      continue;
    }
    techniqueAxis = true;
    for (const auto& name : axis.values) techniques.push_back(&findTechnique(name));
  }
  if (!techniqueAxis) techniques.push_back(&findTechnique(request.defaultTechnique));
  // Keys no technique declares are typos, not axes that happen not to apply.
  auto declaredBySome = [&](const std::string& key) {
    return std::any_of(techniques.begin(), techniques.end(), [&](const Technique* t) { return t->parameter(key); });
  };
  for (const auto& axis : axes)
    if (!declaredBySome(axis.key))
      throw InputError("", std::nullopt, "--grid", fmt::format("no technique of the sweep has the key '{}'", axis.key));
  for (const auto& a : request.assignments) {
    std::string key = a.substr(0, a.find('='));
    if (!declaredBySome(key))
      throw InputError("", std::nullopt, key, fmt::format("--set {}: no technique of the sweep has the key '{}'", a, key));
  }

  SweepPlan plan;
  std::vector<std::vector<std::string>> presetsOf;
  double total = 0;  // a double: a hostile grid's product overflows any integer
  for (const Technique* t : techniques) {
    presetsOf.push_back(sweptPresets(*t, request, plan.notes));
    double count = double(presetsOf.back().size());
    for (const auto& axis : axes) count *= t->parameter(axis.key) ? double(axis.values.size()) : 1.0;
    total += count;
  }
  if (total > double(request.maxConfigurations))
    throw InputError("", std::nullopt, "--grid",
                     fmt::format("{:.0f} configurations are more than --max-configurations ({}); give a larger value to run them all",
                                 total, request.maxConfigurations));
  for (size_t ti = 0; ti < techniques.size(); ++ti) {
    const Technique* t = techniques[ti];
    std::vector<std::string> own;  // the --set assignments this technique declares
    for (const auto& a : request.assignments)
      if (t->parameter(a.substr(0, a.find('=')))) own.push_back(a);
    for (const auto& preset : presetsOf[ti]) {
      std::string name = preset.empty() ? "" : preset;
      if (techniqueAxis) name += fmt::format("{}technique={}", name.empty() ? "" : " ", t->name);
      std::vector<SweepConfig> configs{{name, resolve(*t, preset, own)}};
      for (const auto& axis : axes) {
        if (!t->parameter(axis.key)) continue;
        std::vector<SweepConfig> expanded;
        for (const auto& c : configs)
          for (const auto& value : axis.values) {
            SweepConfig e = c;
            e.settings.assign(axis.key, value);
            e.name += fmt::format("{}{}={}", e.name.empty() ? "" : " ", axis.key, value);
            expanded.push_back(e);
          }
        configs = std::move(expanded);
      }
      plan.configs.insert(plan.configs.end(), configs.begin(), configs.end());
    }
  }
  return plan;
}

const char* sweepRankName(SweepRank rank) { return rank == SweepRank::HaloBand ? "halo_band" : "rmse"; }

double rankedError(const SweepRow& row, SweepRank rank) { return rank == SweepRank::HaloBand ? row.haloRmse : row.rmse; }

void markPareto(std::vector<SweepRow>& rows, SweepRank rank) {
  for (auto& row : rows) {
    const double error = rankedError(row, rank);
    row.pareto = std::none_of(rows.begin(), rows.end(), [&](const SweepRow& other) {
      const double otherError = rankedError(other, rank);
      bool noWorse = other.totalMs <= row.totalMs && otherError <= error;
      bool better = other.totalMs < row.totalMs || otherError < error;
      return &other != &row && noWorse && better;
    });
  }
}

nlohmann::json sweepJson(const SweepInfo& info, const std::vector<SweepRow>& rows) {
  nlohmann::json out;
  out["capture"] = info.capture;
  out["device"] = info.device;
  out["reference"] = info.referenceKind;
  out["frames"] = {info.frameBegin, info.frameEnd};
  out["repeat"] = info.repeat;
  out["warmup"] = info.warmup;
  out["rank_by"] = sweepRankName(info.rank);
  const bool isCounted = info.measure != "time";
  if (isCounted)
    out["cost"] = info.measure + " counted under callgrind (run --cost): per pass, the sum over the frames; total = the compute passes' sum (upload and read-back copies listed, not counted)";
  else
    out["time"] = "GPU ms per frame: per pass, the median over frames x repeats; total = the median over frames x repeats of the sum of the compute passes in that repeat (upload and read-back copies listed, not counted)";
  const std::string passesKey = isCounted ? info.measure : "gpu_ms_median", totalKey = isCounted ? info.measure + "_total" : "gpu_ms_total";
  nlohmann::json list = nlohmann::json::array();
  for (const auto& row : rows) {
    nlohmann::json passes = nlohmann::json::object();
    for (const auto& [name, ms] : row.passMs) passes[name] = ms;
    list.push_back({{"configuration", row.config.name}, {"settings", row.config.settings.toJson()},
                    {passesKey, passes}, {totalKey, row.totalMs}, {"rmse", row.rmse},
                    {"ssim", row.ssim}, {"halo_band_rmse", row.haloRmse}, {"error", row.error}, {"pareto", row.pareto}});
    if (row.sppMax > 0) list.back()["accumulated_spp"] = {row.sppMin, row.sppMax};
  }
  out["rows"] = list;
  return out;
}

std::string sweepCsv(const std::vector<SweepRow>& rows) {
  auto passes = sweepPassNames(rows);
  // Every key of every technique in the sweep, in the order they are first declared.
  std::vector<const Parameter*> keys;
  for (const auto& row : rows)
    for (const auto& p : row.config.settings.technique().parameters)
      if (std::none_of(keys.begin(), keys.end(), [&](const Parameter* k) { return k->key == p.key; })) keys.push_back(&p);
  std::string csv = "configuration,technique";
  for (const auto* k : keys) csv += "," + k->key;
  const std::string unit = rows.empty() ? "ms" : unitOf(rows.front());
  for (const auto& p : passes) csv += fmt::format(",{}_{}", p, unit);
  csv += fmt::format(",total_{},rmse,ssim,pareto\n", unit);
  for (const auto& row : rows) {
    const auto& s = row.config.settings;
    csv += fmt::format("{},{}", csvField(row.config.name), s.technique().name);
    for (const auto* k : keys) csv += "," + (s.has(k->key) ? csvField(s.text(k->key)) : std::string());
    auto number = [&](double v) { return counted(row) ? fmt::format("{:.0f}", v) : fmt::format("{:.6f}", v); };
    for (const auto& p : passes) csv += "," + number(passMs(row, p));
    csv += fmt::format(",{},{:.6f},{:.6f},{}\n", number(row.totalMs), row.rmse, row.ssim, row.pareto ? 1 : 0);
  }
  return csv;
}

std::string SweepRow::samplesLabel() const {
  if (sppMax <= 0) return "";
  return sppMin == sppMax ? fmt::format("{:g} spp", sppMax) : fmt::format("{:g}-{:g} spp", sppMin, sppMax);
}

std::string sweepSvg(const SweepInfo& info, const std::vector<SweepRow>& rows) {
  // Points are numbered (names of grid configurations are long and collide); the key under the
  // plot and each point's hover text give the configuration.
  PlotSeries all{"configurations"};
  all.lines = false;
  std::vector<const SweepRow*> front;
  PlotOptions options;
  std::vector<std::string> sppNotes;
  for (size_t i = 0; i < rows.size(); ++i) {
    const SweepRow& row = rows[i];
    all.x.push_back(row.totalMs);
    all.y.push_back(rankedError(row, info.rank));
    // A ray-traced technique's cost is its samples per pixel: they go with its point and the x axis.
    std::string spp = row.samplesLabel();
    all.labels.push_back(spp.empty() ? std::to_string(i + 1) : fmt::format("{} ({})", i + 1, spp));
    all.tooltips.push_back(fmt::format("{}: {}{}, {:.4g} {}, RMSE {:.5g}, halo-band RMSE {:.5g}{}", i + 1, row.config.name,
                                       spp.empty() ? "" : ", " + spp, row.totalMs, unitOf(row), row.rmse, row.haloRmse,
                                       row.pareto ? " (Pareto-optimal)" : ""));
    all.highlighted.push_back(row.pareto);
    options.key.push_back(fmt::format("{} = {}{}", i + 1, row.config.name, spp.empty() ? "" : " (" + spp + " accumulated)"));
    if (!spp.empty()) sppNotes.push_back(fmt::format("{}: {}", i + 1, spp));
    if (row.pareto) front.push_back(&row);
  }
  std::sort(front.begin(), front.end(), [](const SweepRow* a, const SweepRow* b) { return a->totalMs < b->totalMs; });
  PlotSeries pareto{"Pareto front"};
  pareto.markers = false;
  for (const auto* row : front) {
    pareto.x.push_back(row->totalMs);
    pareto.y.push_back(rankedError(*row, info.rank));
  }
  const bool band = info.rank == SweepRank::HaloBand;
  const bool isCounted = info.measure != "time";
  options.title = fmt::format("{}: {} vs {} reference against {}", info.capture, band ? "halo-band RMSE" : "RMSE",
                              info.referenceKind, isCounted ? info.measure : "GPU time");
  options.xLabel = isCounted ? info.measure + " over the frames (counted under callgrind, compute passes)"
                             : "GPU time per frame (ms, sum of pass medians)";
  if (!sppNotes.empty()) options.xLabel += fmt::format("; samples per pixel {}", fmt::join(sppNotes, ", "));
  options.yLabel = band ? "halo-band RMSE (visibility, 0-1; the background behind nearer silhouettes)"
                       : "RMSE (visibility, 0-1; sky masked)";
  options.logX = true;
  return svgPlot({pareto, all}, options);
}

namespace {

// A pass's median ms, or "-" where the configuration did not run the pass (not 0: it took no time
// because it was not there).
std::string msCell(const SweepRow& row, const std::string& pass, size_t width) {
  const bool ran = std::any_of(row.passMs.begin(), row.passMs.end(), [&](const auto& e) { return e.first == pass; });
  return ran ? costText(row, passMs(row, pass), width) : fmt::format("{:>{}}", "-", width);
}

// Timed columns are 10 wide; counted ones 18 (an instruction count runs to 10-11 digits).
size_t costWidth(const std::vector<const SweepRow*>& rows) { return rows.empty() || !counted(*rows.front()) ? 10 : 18; }

size_t nameWidth(const std::vector<const SweepRow*>& rows) {
  size_t width = 13;
  for (const auto* row : rows) width = std::max(width, row->config.name.size());
  return width;
}

// Every pass name of the rows, in first-seen order.
std::vector<std::string> passNames(const std::vector<const SweepRow*>& rows) {
  std::vector<std::string> names;
  for (const auto* row : rows)
    for (const auto& [name, ms] : row->passMs)
      if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  return names;
}

// Rows' pass times, the passes as columns, with their total, errors and Pareto flag: the table of
// a sweep of one technique.
std::string passTable(const std::vector<const SweepRow*>& rows) {
  const size_t width = nameWidth(rows);
  const std::vector<std::string> passes = passNames(rows);
  std::string table = fmt::format("{:<{}}", "configuration", width);
  for (const auto& p : passes) table += fmt::format(" {:>{}}", p, std::max<size_t>(p.size(), 8));
  const size_t cost = costWidth(rows);
  table += fmt::format(" {:>{}} {:>9} {:>9} {:>7} {:>6}", "total " + unitOf(*rows.front()), cost, "RMSE", "halo RMSE", "SSIM", "pareto");
  table += "\n";
  for (const auto* row : rows) {
    table += fmt::format("{:<{}}", row->config.name, width);
    for (const auto& p : passes) table += " " + msCell(*row, p, std::max<size_t>(p.size(), cost == 10 ? 8 : 12));
    table += fmt::format(" {} {:>9.5f} {:>9.5f} {:>7.4f} {:>6}", costText(*row, row->totalMs, cost), row->rmse, row->haloRmse,
                         row->ssim, row->pareto ? "*" : "");
    table += "\n";
  }
  return table;
}

constexpr size_t kTerminalColumns = 120;

std::string totalsTable(const std::vector<const SweepRow*>& rows) {
  const size_t width = nameWidth(rows);
  const size_t cost = costWidth(rows);
  std::string table = fmt::format("{:>3} {:<{}} {:>{}} {:>9} {:>9} {:>10} {:>7} {:>6}\n", "#", "configuration", width,
                                  "total " + unitOf(*rows.front()), cost, "RMSE", "halo RMSE", "halo bias", "SSIM", "pareto");
  for (size_t i = 0; i < rows.size(); ++i) {
    const SweepRow* row = rows[i];
    table += fmt::format("{:>3} {:<{}} {} {:>9.5f} {:>9.5f} {:>+10.4f} {:>7.4f} {:>6}\n", i + 1, row->config.name, width,
                         costText(*row, row->totalMs, cost), row->rmse, row->haloRmse, row->haloBias, row->ssim,
                         row->pareto ? "*" : "");
  }
  return table;
}

// One technique's passes (rows) against its configurations (columns, by their # in the totals
// table), split into blocks of columns so that no line passes 120 characters.
std::string techniquePassTable(const std::vector<const SweepRow*>& rows, const std::vector<size_t>& numbers) {
  const std::vector<std::string> passes = passNames(rows);
  size_t width = 4;
  for (const auto& p : passes) width = std::max(width, p.size());
  const size_t cell = costWidth(rows) == 10 ? 9 : 14;
  const size_t perBlock = std::max<size_t>(1, (kTerminalColumns - width) / (cell + 1));
  std::string table;
  for (size_t first = 0; first < rows.size(); first += perBlock) {
    const size_t last = std::min(rows.size(), first + perBlock);
    table += fmt::format("{:<{}}", "pass", width);
    for (size_t c = first; c < last; ++c) table += fmt::format(" {:>{}}", fmt::format("#{}", numbers[c]), cell);
    table += "\n";
    for (const auto& p : passes) {
      table += fmt::format("{:<{}}", p, width);
      for (size_t c = first; c < last; ++c) table += " " + msCell(*rows[c], p, cell);
      table += "\n";
    }
  }
  return table;
}

}  // namespace

std::vector<std::string> sweepTechniques(const std::vector<SweepRow>& rows) {
  std::vector<std::string> names;
  for (const auto& row : rows)
    if (std::find(names.begin(), names.end(), row.config.settings.technique().name) == names.end())
      names.push_back(row.config.settings.technique().name);
  return names;
}

std::string sweepTable(const std::vector<SweepRow>& rows) {
  std::vector<const SweepRow*> all;
  for (const auto& row : rows) all.push_back(&row);
  const auto techniques = sweepTechniques(rows);
  if (techniques.size() <= 1) return passTable(all);
  std::string text = totalsTable(all);
  for (const auto& technique : techniques) {
    std::vector<const SweepRow*> own;
    std::vector<size_t> numbers;
    for (size_t i = 0; i < all.size(); ++i)
      if (all[i]->config.settings.technique().name == technique) own.push_back(all[i]), numbers.push_back(i + 1);
    text += (counted(*own.front()) ? fmt::format("\n{}: {} per pass and configuration (#, over the frames)\n", technique,
                                                 own.front()->measure)
                                   : fmt::format("\n{}: GPU ms per pass and configuration (#, median per frame)\n", technique)) +
            techniquePassTable(own, numbers);
  }
  return text;
}

std::vector<std::string> sweepPassNames(const std::vector<SweepRow>& rows) {
  std::vector<const SweepRow*> pointers;
  for (const auto& row : rows) pointers.push_back(&row);
  return passNames(pointers);
}

SweepRow sweepRow(const SweepConfig& config, const RunResults& results) {
  SweepRow row{config};
  if (results.replay.cost == CostMeasure::Time) {
    for (const auto& [name, durations] : samplesByPass(results.replay)) row.passMs.emplace_back(name, summarize(durations).median);
    row.totalMs = totalMedianMs(timedFrames(results.replay));
  } else {
    row.measure = costMeasureName(results.replay.cost);
    for (const auto& [name, perFrame] : countsByPass(results.replay, results.replay.cost)) {
      row.passMs.emplace_back(name, std::accumulate(perFrame.begin(), perFrame.end(), 0.0));
      if (!isHostCopyPass(name)) row.totalMs += row.passMs.back().second;
    }
  }
  row.error = results.analysis.summaryJson()["error"];
  row.rmse = row.error["rmse"].get<double>();
  row.ssim = row.error["ssim"].get<double>();
  const auto& band = row.error["halo_band"];
  row.haloPixels = band["pixels"].get<int64_t>();
  row.haloRmse = band["rmse"].get<double>();
  row.haloBias = band["bias"].get<double>();
  const std::string& samples = config.settings.technique().samplesValue;
  if (samples.empty()) return row;
  for (const auto& frame : results.replay.frames)
    if (auto spp = frame.techniqueValues.find(samples); spp != frame.techniqueValues.end()) {
      row.sppMin = row.sppMin == 0 ? spp->second : std::min(row.sppMin, spp->second);
      row.sppMax = std::max(row.sppMax, spp->second);
    }
  return row;
}

}  // namespace aor
