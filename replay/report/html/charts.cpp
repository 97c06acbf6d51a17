#include "report/html/charts.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "report/html/colour_map.h"
#include "report/html/html_page.h"

namespace aor::html {
namespace {

constexpr const char* kBaselineColour = "#1f77b4";
constexpr const char* kNewColour = "#d62728";

// Linear axis ticks: 1, 2 or 5 times a power of ten, about `count` of them in [lo, hi].
std::vector<double> ticksBetween(double lo, double hi, int count) {
  double raw = (hi - lo) / count;
  if (!(raw > 0)) return {lo};
  double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  double f = raw / magnitude;
  double step = (f < 1.5 ? 1 : f < 3.5 ? 2 : f < 7.5 ? 5 : 10) * magnitude;
  std::vector<double> out;
  for (double v = std::ceil(lo / step) * step; v <= hi + step * 1e-9; v += step) out.push_back(std::abs(v) < step * 1e-9 ? 0 : v);
  return out;
}

std::string number(double v) { return fmt::format("{:.4g}", v); }

double quantile(std::vector<double> values, double q) {
  std::sort(values.begin(), values.end());
  double position = q * double(values.size() - 1);
  size_t i = size_t(position);
  if (i + 1 >= values.size()) return values.back();
  return values[i] + (values[i + 1] - values[i]) * (position - double(i));
}

}  // namespace

double niceCeiling(double value) {
  if (!(value > 0) || !std::isfinite(value)) return 1.0;
  double magnitude = std::pow(10.0, std::floor(std::log10(value)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (value <= m * magnitude * (1 + 1e-12)) return m * magnitude;
  return 10 * magnitude;
}

std::string barChartSvg(const std::vector<Bar>& bars, const std::string& axisLabel) {
  constexpr double kLeft = 190, kRight = 30, kRow = 26, kTop = 10, kBottom = 46, kWidth = 760;
  double height = kTop + kRow * double(bars.size()) + kBottom;
  double hi = 0;
  for (const auto& b : bars) hi = std::max(hi, b.max);
  hi = niceCeiling(hi > 0 ? hi * 1.05 : 1.0);
  auto px = [&](double v) { return kLeft + v / hi * (kWidth - kLeft - kRight); };
  std::string svg = fmt::format(R"(<svg xmlns="http://www.w3.org/2000/svg" class="bars" width="{0}" height="{1}" viewBox="0 0 {0} {1}" font-size="12">)" "\n",
                                kWidth, height);
  double bottom = kTop + kRow * double(bars.size());
  for (double t : ticksBetween(0, hi, 6))
    svg += fmt::format(R"(<line x1="{0:.1f}" y1="{1}" x2="{0:.1f}" y2="{2}" stroke="#e4e4e4"/><text x="{0:.1f}" y="{3}" text-anchor="middle">{4}</text>)" "\n",
                       px(t), kTop, bottom, bottom + 16, number(t));
  for (size_t i = 0; i < bars.size(); ++i) {
    const Bar& b = bars[i];
    double y = kTop + kRow * double(i), mid = y + kRow / 2;
    svg += fmt::format(R"(<text x="{}" y="{:.1f}" text-anchor="end">{}</text>)" "\n", kLeft - 8, mid + 4, escape(b.name));
    svg += fmt::format(R"(<rect x="{:.1f}" y="{:.1f}" width="{:.1f}" height="{:.1f}" fill="#7fa7cf"><title>{}: median {} (min {}, max {})</title></rect>)" "\n",
                       kLeft, y + 5, std::max(0.5, px(b.median) - kLeft), kRow - 10, escape(b.name), number(b.median),
                       number(b.min), number(b.max));
    svg += fmt::format(R"(<line x1="{0:.1f}" y1="{2:.1f}" x2="{1:.1f}" y2="{2:.1f}" stroke="#222"/><line x1="{0:.1f}" y1="{3:.1f}" x2="{0:.1f}" y2="{4:.1f}" stroke="#222"/><line x1="{1:.1f}" y1="{3:.1f}" x2="{1:.1f}" y2="{4:.1f}" stroke="#222"/>)" "\n",
                       px(b.min), px(b.max), mid, mid - 5, mid + 5);
  }
  svg += fmt::format(R"(<line x1="{0}" y1="{1}" x2="{2}" y2="{1}" stroke="#444"/><text x="{3:.1f}" y="{4}" text-anchor="middle">{5}</text>)" "\n",
                     kLeft, bottom, kWidth - kRight, (kLeft + kWidth - kRight) / 2, bottom + 36, escape(axisLabel));
  return svg + "</svg>\n";
}

std::string colourScaleSvg(const std::string& label, double lo, double hi, bool diverging) {
  constexpr double kWidth = 320, kBarLeft = 10, kBarWidth = 300;
  std::string svg = fmt::format(R"(<svg xmlns="http://www.w3.org/2000/svg" class="colour-scale" width="{}" height="56" viewBox="0 0 {} 56" font-size="11">)" "\n",
                                kWidth, kWidth);
  constexpr int kSteps = 60;
  for (int i = 0; i < kSteps; ++i) {
    double t = (i + 0.5) / kSteps;
    auto colour = diverging ? divergingColour(2 * t - 1) : sequentialColour(t);
    svg += fmt::format(R"(<rect x="{:.2f}" y="6" width="{:.2f}" height="14" fill="{}"/>)", kBarLeft + kBarWidth * i / kSteps,
                       kBarWidth / kSteps + 0.3, cssColour(colour));
  }
  for (double f : {0.0, 0.5, 1.0})
    svg += fmt::format(R"(<text x="{:.1f}" y="33" text-anchor="middle">{}</text>)", kBarLeft + kBarWidth * f, number(lo + (hi - lo) * f));
  svg += fmt::format(R"(<text x="{:.1f}" y="50" text-anchor="middle">{}</text>)", kBarLeft + kBarWidth / 2, escape(label));
  return svg + "\n</svg>\n";
}

std::string stripPlotSvg(const StripPlot& plot) {
  constexpr double kWidth = 560, kLeft = 70, kRight = 20, kHeight = 120;
  std::vector<double> all = plot.baseline;
  all.insert(all.end(), plot.candidate.begin(), plot.candidate.end());
  all.push_back(plot.bandLow);
  all.push_back(plot.bandHigh);
  double lo = *std::min_element(all.begin(), all.end()), hi = *std::max_element(all.begin(), all.end());
  double pad = std::max((hi - lo) * 0.08, std::abs(hi) * 1e-3 + 1e-9);
  lo -= pad;
  hi += pad;
  auto px = [&](double v) { return kLeft + (v - lo) / (hi - lo) * (kWidth - kLeft - kRight); };
  std::string svg = fmt::format(R"(<svg xmlns="http://www.w3.org/2000/svg" class="strip" width="{0}" height="{1}" viewBox="0 0 {0} {1}" font-size="11">)" "\n",
                                kWidth, kHeight);
  svg += fmt::format(R"(<rect x="{:.1f}" y="8" width="{:.1f}" height="70" fill="#ffe9a8"><title>threshold: a new median inside [{} ms, {} ms] is not a change</title></rect>)" "\n",
                     px(plot.bandLow), std::max(1.0, px(plot.bandHigh) - px(plot.bandLow)), number(plot.bandLow), number(plot.bandHigh));
  auto row = [&](const std::vector<double>& values, double y, const char* colour, const char* side) {
    if (values.empty()) return;
    double q1 = quantile(values, 0.25), q2 = quantile(values, 0.5), q3 = quantile(values, 0.75);
    svg += fmt::format(R"(<text x="{}" y="{:.1f}" text-anchor="end">{}</text>)" "\n", kLeft - 6, y + 4, side);
    svg += fmt::format(R"(<rect x="{:.1f}" y="{:.1f}" width="{:.1f}" height="20" fill="none" stroke="{}"/>)" "\n", px(q1), y - 10,
                       std::max(0.5, px(q3) - px(q1)), colour);
    svg += fmt::format(R"(<line x1="{0:.1f}" y1="{1:.1f}" x2="{0:.1f}" y2="{2:.1f}" stroke="{3}" stroke-width="3"><title>{4} median {5} ms</title></line>)" "\n",
                       px(q2), y - 12, y + 12, colour, side, number(q2));
    for (size_t i = 0; i < values.size(); ++i) {
      double jitter = (double((i * 7919) % 13) - 6.0) * 0.9;  // deterministic spread so equal values stay visible
      svg += fmt::format(R"(<circle cx="{:.1f}" cy="{:.1f}" r="2.5" fill="{}" fill-opacity="0.6"><title>{} ms</title></circle>)", px(values[i]),
                         y + jitter, colour, number(values[i]));
    }
    svg += "\n";
  };
  row(plot.baseline, 28, kBaselineColour, "baseline");
  row(plot.candidate, 60, kNewColour, "new");
  for (double t : ticksBetween(lo, hi, 5))
    svg += fmt::format(R"(<text x="{:.1f}" y="94" text-anchor="middle">{}</text>)", px(t), number(t));
  svg += fmt::format(R"(<line x1="{0}" y1="80" x2="{1}" y2="80" stroke="#444"/><text x="{2:.1f}" y="112" text-anchor="middle">GPU time (ms); shaded: the threshold band around the baseline median</text>)" "\n",
                     kLeft, kWidth - kRight, (kLeft + kWidth - kRight) / 2);
  return svg + "</svg>\n";
}

}  // namespace aor::html
