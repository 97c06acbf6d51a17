#include "report/temporal_plot.h"

#include <cmath>

#include <fmt/format.h>

#include "report/run_outputs.h"
#include "report/svg_plot.h"

namespace aor {
namespace {

PlotSeries perFrameSeries(const nlohmann::json& frames, const std::string& key, const std::string& name) {
  PlotSeries s{name, {}, {}};
  for (const auto& f : frames) {
    const auto* metrics = f.contains("metrics") ? &f["metrics"] : nullptr;
    if (!metrics || !metrics->contains("temporal") || !(*metrics)["temporal"].contains(key)) continue;
    s.x.push_back(f["index"].get<double>());
    s.y.push_back((*metrics)["temporal"][key].get<double>());
  }
  return s;
}

void writePerFramePlot(const std::filesystem::path& outDir, const nlohmann::json& report, const std::string& noHistoryReason) {
  const auto& frames = report["frames"];
  std::vector<PlotSeries> series;
  for (auto [key, name] : {std::pair{"warping_error", "warping error (MSE vs previous output, reprojected)"},
                           std::pair{"derivative_error", "derivative error |dO - dR|"},
                           std::pair{"abs_error", "abs error |O - R|"}})
    if (auto s = perFrameSeries(frames, key, name); !s.x.empty()) series.push_back(std::move(s));
  if (series.empty()) return;
  PlotOptions options;
  options.title = fmt::format("{}: temporal stability per frame", report["capture"].value("name", ""));
  options.xLabel = "frame (index in the capture); dashed: history reset";
  options.yLabel = "error (visibility, 0-1; warping error: squared)";
  options.logY = true;  // warping error (MSE) sits orders of magnitude below the absolute errors
  for (const auto& f : frames)
    if (f.value("history", "") == "reset" && (noHistoryReason.empty() || f.value("reset_reason", "") != noHistoryReason)) {
      options.verticalMarkers.push_back(f["index"].get<double>());
      options.verticalMarkerLabels.push_back(f.value("reset_reason", "reset"));
    }
  writeText(outDir / "temporal.svg", svgPlot(series, options));
}

void writeResponsePlot(const std::filesystem::path& outDir, const nlohmann::json& temporal) {
  if (!temporal.contains("disocclusion") || temporal["disocclusion"].is_null()) return;
  const auto& d = temporal["disocclusion"];
  auto curve = d["abs_error_by_age"].get<std::vector<double>>();
  if (curve.size() < 2) return;
  double settled = d["settled_error"].get<double>(), w = temporal["history_weight"].get<double>();
  PlotSeries measured{"abs error of disoccluded pixels", {}, curve};
  PlotSeries predicted{"EMA ghost bound: settled + excess(0) * w^n", {}, {}};
  predicted.markers = false;
  for (size_t n = 0; n < curve.size(); ++n) {
    measured.x.push_back(double(n));
    predicted.x.push_back(double(n));
    predicted.y.push_back(settled + std::max(0.0, curve[0] - settled) * std::pow(w, double(n)));
  }
  PlotOptions options;
  options.title = fmt::format("response after disocclusion (history weight {:g})", w);
  options.xLabel = "frames since disocclusion (frames)";
  options.yLabel = "mean |O - R| (visibility, 0-1)";
  writeText(outDir / "temporal_response.svg", svgPlot({measured, predicted}, options));
}

}  // namespace

void writeTemporalPlots(const std::filesystem::path& outDir, const nlohmann::json& report, const std::string& noHistoryReason) {
  if (!report.contains("frames") || report["frames"].size() < 2) return;
  writePerFramePlot(outDir, report, noHistoryReason);
  if (report.contains("metrics") && report["metrics"].contains("temporal")) writeResponsePlot(outDir, report["metrics"]["temporal"]);
}

}  // namespace aor
