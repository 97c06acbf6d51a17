#include "report/sweep.h"

#include <algorithm>
#include <sstream>

#include <fmt/format.h>

#include "capture/input_error.h"
#include "report/svg_plot.h"

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

void applyAxisValue(AoSettings& settings, const std::string& key, const std::string& value) {
  if (key == "technique")
    applyTechnique(settings, parseTechnique(value));
  else
    applySetting(settings, key + "=" + value);
}

// Numbers as the user would write them in a table: no trailing zeros, finite precision.
std::string number(double v) { return fmt::format("{:.6g}", v); }

std::vector<std::string> passNames(const std::vector<SweepRow>& rows) {
  std::vector<std::string> names;
  for (const auto& row : rows)
    for (const auto& [name, ms] : row.passMs)
      if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  return names;
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

}  // namespace

std::vector<SweepConfig> expandSweep(const AoSettings& base, const std::vector<std::string>& presets,
                                     const std::vector<std::string>& grid) {
  std::vector<GridAxis> axes;
  for (const auto& g : grid) axes.push_back(parseAxis(g));
  std::vector<SweepConfig> configs;
  for (const auto& preset : presets) {
    SweepConfig c{preset, base};
    applyPreset(c.settings, preset);
    configs.push_back(c);
  }
  for (const auto& axis : axes) {
    std::vector<SweepConfig> expanded;
    for (const auto& c : configs)
      for (const auto& value : axis.values) {
        SweepConfig e = c;
        applyAxisValue(e.settings, axis.key, value);
        e.name += fmt::format(" {}={}", axis.key, value);
        expanded.push_back(e);
      }
    configs = std::move(expanded);
  }
  return configs;
}

void markPareto(std::vector<SweepRow>& rows) {
  for (auto& row : rows) {
    row.pareto = std::none_of(rows.begin(), rows.end(), [&](const SweepRow& other) {
      bool noWorse = other.totalMs <= row.totalMs && other.rmse <= row.rmse;
      bool better = other.totalMs < row.totalMs || other.rmse < row.rmse;
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
  out["time"] = "GPU ms per frame: per pass, the median over frames x repeats; total = the median over frames x repeats of the sum of the compute passes in that repeat (upload and read-back copies listed, not counted)";
  nlohmann::json list = nlohmann::json::array();
  for (const auto& row : rows) {
    nlohmann::json passes = nlohmann::json::object();
    for (const auto& [name, ms] : row.passMs) passes[name] = ms;
    list.push_back({{"configuration", row.config.name}, {"settings", toJson(row.config.settings)},
                    {"gpu_ms_median", passes}, {"gpu_ms_total", row.totalMs}, {"rmse", row.rmse},
                    {"ssim", row.ssim}, {"error", row.error}, {"pareto", row.pareto}});
  }
  out["rows"] = list;
  return out;
}

std::string sweepCsv(const std::vector<SweepRow>& rows) {
  auto passes = passNames(rows);
  std::string csv = "configuration,technique,slices,steps,radius,falloff,thin,spatial,temporal";
  for (const auto& p : passes) csv += fmt::format(",{}_ms", p);
  csv += ",total_ms,rmse,ssim,pareto\n";
  for (const auto& row : rows) {
    const auto& s = row.config.settings;
    csv += fmt::format("{},{},{},{},{},{},{},{},{}", csvField(row.config.name), techniqueName(s.technique), s.slices,
                       s.steps, number(s.radius), number(s.falloff), number(s.thin), s.spatial, number(s.temporal));
    for (const auto& p : passes) csv += fmt::format(",{:.6f}", passMs(row, p));
    csv += fmt::format(",{:.6f},{:.6f},{:.6f},{}\n", row.totalMs, row.rmse, row.ssim, row.pareto ? 1 : 0);
  }
  return csv;
}

std::string sweepSvg(const SweepInfo& info, const std::vector<SweepRow>& rows) {
  PlotSeries all{"configurations"};
  all.lines = false;
  std::vector<const SweepRow*> front;
  for (const auto& row : rows) {
    all.x.push_back(row.totalMs);
    all.y.push_back(row.rmse);
    all.labels.push_back(row.config.name);
    all.highlighted.push_back(row.pareto);
    if (row.pareto) front.push_back(&row);
  }
  std::sort(front.begin(), front.end(), [](const SweepRow* a, const SweepRow* b) { return a->totalMs < b->totalMs; });
  PlotSeries pareto{"Pareto front"};
  pareto.markers = false;
  for (const auto* row : front) {
    pareto.x.push_back(row->totalMs);
    pareto.y.push_back(row->rmse);
  }
  PlotOptions options;
  options.title = fmt::format("{}: RMSE vs {} reference against GPU time", info.capture, info.referenceKind);
  options.xLabel = "GPU ms per frame (sum of pass medians)";
  options.yLabel = "RMSE of visibility (sky masked)";
  options.logX = true;
  return svgPlot({pareto, all}, options);
}

std::string sweepTable(const std::vector<SweepRow>& rows) {
  size_t nameWidth = 13;
  for (const auto& row : rows) nameWidth = std::max(nameWidth, row.config.name.size());
  auto passes = passNames(rows);
  std::string table = fmt::format("{:<{}}", "configuration", nameWidth);
  for (const auto& p : passes) table += fmt::format(" {:>{}}", p, std::max<size_t>(p.size(), 8));
  table += fmt::format(" {:>10} {:>9} {:>7} {:>6}\n", "total ms", "RMSE", "SSIM", "pareto");
  for (const auto& row : rows) {
    table += fmt::format("{:<{}}", row.config.name, nameWidth);
    for (const auto& p : passes) table += fmt::format(" {:>{}.3f}", passMs(row, p), std::max<size_t>(p.size(), 8));
    table += fmt::format(" {:>10.3f} {:>9.5f} {:>7.4f} {:>6}\n", row.totalMs, row.rmse, row.ssim, row.pareto ? "*" : "");
  }
  return table;
}

}  // namespace aor
