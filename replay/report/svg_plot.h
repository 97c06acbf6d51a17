#pragma once
// Small, dependency-free SVG charts for reports (error vs time, per-frame curves): readable in any
// browser, no plotting tool needed. Deterministic output for the same data.
#include <string>
#include <string_view>
#include <vector>

namespace aor {

struct PlotSeries {
  std::string name;
  std::vector<double> x, y;
  bool lines = true;             // connect points in order
  bool markers = true;
  std::vector<std::string> labels;  // optional per-point labels (same length as x), drawn beside points
                                    // where they overlap nothing, else further out with a leader line
  std::vector<std::string> tooltips;  // optional per-point hover text (an SVG <title>), same length
  std::vector<bool> highlighted;    // optional per-point emphasis (e.g. Pareto-optimal), same length
};

struct PlotOptions {
  std::string title;
  std::string xLabel, yLabel;
  bool logX = false, logY = false;
  int width = 800, height = 500;
  std::vector<double> verticalMarkers;  // e.g. frames where history was reset
  std::vector<std::string> verticalMarkerLabels;  // optional, one per marker: drawn up its line
  std::vector<std::string> key;  // optional lines under the plot, e.g. "1 = high" for numbered labels
};

std::string svgPlot(const std::vector<PlotSeries>& series, const PlotOptions& options);

// Text for XML and HTML (SVG, report pages, JUnit): & < > " ' as entities.
std::string escapeXml(std::string_view text);

}  // namespace aor
