#pragma once
// SVG charts of the HTML reports that report/svg_plot.h (x-y lines and points) does not draw:
// bars with whiskers, colour scales and two-sample strip plots. Every mark has a <title>, so a
// hover shows its exact value.
#include <string>
#include <vector>

namespace aor::html {

struct Bar {
  std::string name;
  double median = 0, min = 0, max = 0;
};
// Horizontal bars at the median with min-max whiskers; `unit` labels the axis ("GPU time (ms)").
std::string barChartSvg(const std::vector<Bar>& bars, const std::string& axisLabel);

// A horizontal colour bar from lo to hi for an image's scale; `diverging` picks the signed map.
std::string colourScaleSvg(const std::string& label, double lo, double hi, bool diverging);

struct StripPlot {
  std::string name;
  std::vector<double> baseline, candidate;  // values in ms
  double bandLow = 0, bandHigh = 0;         // the baseline median scaled by the verdict's threshold, both ways
  std::string verdict;
};
// Both distributions as dots (with quartile boxes and medians) on one ms axis, the band a new
// median must leave to count drawn around the baseline's.
std::string stripPlotSvg(const StripPlot& plot);

// Nice round upper end of a scale that holds `value` (1, 2 or 5 times a power of ten).
double niceCeiling(double value);

}  // namespace aor::html
