#include "report/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "core/plain_text.h"

namespace aor {
namespace {

// Distinct on white and in grayscale print; cycled when there are more series.
constexpr const char* kPalette[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#17becf"};
constexpr double kMarginLeft = 78, kMarginRight = 24, kMarginTop = 62, kMarginBottom = 56;


bool usable(double v, bool logScale) { return std::isfinite(v) && (!logScale || v > 0); }

// One axis: data range (in plotted units, i.e. log10 when logarithmic) mapped onto pixels.
struct Axis {
  bool log = false;
  double lo = 0, hi = 1;
  double pixelLo = 0, pixelHi = 1;

  double transform(double v) const { return log ? std::log10(v) : v; }
  double toPixel(double v) const { return pixelLo + (transform(v) - lo) / (hi - lo) * (pixelHi - pixelLo); }
};

// Finite data range of every point that can be drawn on this axis; [0,1] when there is none.
std::pair<double, double> dataRange(const std::vector<PlotSeries>& series, bool isX, bool logScale, bool otherLog) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& s : series)
    for (size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      double v = isX ? s.x[i] : s.y[i], other = isX ? s.y[i] : s.x[i];
      if (!usable(v, logScale) || !usable(other, otherLog)) continue;
      v = logScale ? std::log10(v) : v;
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  if (!(lo <= hi)) return {0.0, 1.0};
  if (hi - lo < 1e-12 * std::max(1.0, std::abs(hi))) {  // a single value: give it some room
    double pad = logScale ? 0.5 : std::max(std::abs(hi) * 0.1, 1e-9);
    return {lo - pad, hi + pad};
  }
  double pad = (hi - lo) * 0.06;
  return {lo - pad, hi + pad};
}

// 1, 2 or 5 times a power of ten, about range/targetCount.
double niceStep(double range, int targetCount) {
  double raw = range / targetCount;
  double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  double fraction = raw / magnitude;
  double nice = fraction < 1.5 ? 1 : fraction < 3.5 ? 2 : fraction < 7.5 ? 5 : 10;
  return nice * magnitude;
}

std::vector<double> linearTicks(double lo, double hi, bool positiveOnly) {
  std::vector<double> out;
  double step = niceStep(hi - lo, 6);
  for (double v = std::ceil(lo / step) * step; v <= hi + step * 1e-9; v += step)
    if (!positiveOnly || v > step * 1e-9) out.push_back(std::abs(v) < step * 1e-9 ? 0.0 : v);
  return out;
}

// Tick values in data units.
std::vector<double> ticks(const Axis& axis) {
  std::vector<double> out;
  if (axis.log) {
    bool fewDecades = axis.hi - axis.lo < 1.5;
    for (int e = int(std::floor(axis.lo)); e <= int(std::ceil(axis.hi)); ++e)
      for (double m : fewDecades ? std::vector<double>{1, 2, 5} : std::vector<double>{1}) {
        double v = m * std::pow(10.0, e);
        if (std::log10(v) >= axis.lo && std::log10(v) <= axis.hi) out.push_back(v);
      }
    if (out.size() >= 3) return out;
    // Less than about a decade: evenly spaced values read better than one or two powers of ten.
    return linearTicks(std::pow(10.0, axis.lo), std::pow(10.0, axis.hi), true);
  }
  return linearTicks(axis.lo, axis.hi, false);
}

std::string tickLabel(double v) {
  double a = std::abs(v);
  if (a != 0 && (a < 1e-3 || a >= 1e5)) return fmt::format("{:.0e}", v);
  return fmt::format("{:g}", v);
}

void drawAxes(std::string& svg, const Axis& x, const Axis& y, const PlotOptions& o) {
  double left = x.pixelLo, right = x.pixelHi, top = y.pixelHi, bottom = y.pixelLo;
  for (double v : ticks(x)) {
    double px = x.toPixel(v);
    svg += fmt::format(R"(<line x1="{:.1f}" y1="{:.1f}" x2="{:.1f}" y2="{:.1f}" stroke="#e4e4e4"/>)" "\n", px, top, px, bottom);
    svg += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" text-anchor="middle">{}</text>)" "\n", px, bottom + 18, tickLabel(v));
  }
  for (double v : ticks(y)) {
    double py = y.toPixel(v);
    svg += fmt::format(R"(<line x1="{:.1f}" y1="{:.1f}" x2="{:.1f}" y2="{:.1f}" stroke="#e4e4e4"/>)" "\n", left, py, right, py);
    svg += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" text-anchor="end">{}</text>)" "\n", left - 6, py + 4, tickLabel(v));
  }
  svg += fmt::format(R"(<rect x="{:.1f}" y="{:.1f}" width="{:.1f}" height="{:.1f}" fill="none" stroke="#444"/>)" "\n",
                     left, top, right - left, bottom - top);
  svg += fmt::format(R"(<text x="{:.1f}" y="24" text-anchor="middle" font-size="16" font-weight="bold">{}</text>)" "\n",
                     (left + right) / 2, escapeXml(o.title));
  svg += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" text-anchor="middle">{}{}</text>)" "\n", (left + right) / 2,
                     bottom + 40, escapeXml(o.xLabel), x.log ? " (log scale)" : "");
  svg += fmt::format(R"svg(<text transform="translate(18 {:.1f}) rotate(-90)" text-anchor="middle">{}{}</text>)svg" "\n",
                     (top + bottom) / 2, escapeXml(o.yLabel), y.log ? " (log scale)" : "");
}

void drawVerticalMarkers(std::string& svg, const Axis& x, const Axis& y, const PlotOptions& o) {
  for (size_t k = 0; k < o.verticalMarkers.size(); ++k) {
    double v = o.verticalMarkers[k];
    if (!usable(v, x.log)) continue;
    double px = x.toPixel(v);
    if (px < x.pixelLo || px > x.pixelHi) continue;
    svg += fmt::format(R"(<line x1="{:.1f}" y1="{:.1f}" x2="{:.1f}" y2="{:.1f}" stroke="#888" stroke-dasharray="5 4"/>)" "\n",
                       px, y.pixelHi, px, y.pixelLo);
    if (k < o.verticalMarkerLabels.size() && !o.verticalMarkerLabels[k].empty())  // up the line: labels of near markers never cross
      svg += fmt::format(R"svg(<text transform="translate({:.1f} {:.1f}) rotate(-90)" text-anchor="end" font-size="10" fill="#555">{}</text>)svg" "\n",
                         px - 3, y.pixelHi + 4, escapeXml(o.verticalMarkerLabels[k]));
  }
}

// Rectangles of text already placed and of points, in pixels: labels go where they overlap none.
struct Box {
  double left, top, right, bottom;
  bool overlaps(const Box& o) const { return left < o.right && o.left < right && top < o.bottom && o.top < bottom; }
};
constexpr double kLabelCharWidth = 6.4, kLabelHeight = 11;

Box labelBox(double anchorX, double baselineY, size_t chars, bool rightAligned) {
  double width = kLabelCharWidth * double(chars);
  double left = rightAligned ? anchorX - width : anchorX;
  return {left, baselineY - kLabelHeight + 2, left + width, baselineY + 2};
}

// Where a point's label goes: the first spot, nearest first, in eight directions around it that
// stays inside the plot and overlaps no placed label or point. Returns the anchor, alignment and
// whether a leader line is needed (spots beyond the nearest ring).
struct LabelSpot {
  double x, y;
  bool rightAligned, leader;
};

LabelSpot placeLabel(double px, double py, size_t chars, const Axis& x, const Axis& y, std::vector<Box>& taken) {
  static constexpr double kDirections[8][2] = {{1, -1}, {1, 1}, {-1, -1}, {-1, 1}, {1, 0}, {-1, 0}, {0, -1}, {0, 1}};
  for (double radius : {8.0, 20.0, 34.0, 50.0, 70.0})
    for (const auto& d : kDirections) {
      bool right = d[0] < 0;
      double ax = px + d[0] * radius, ay = py + d[1] * radius + (d[1] > 0 ? kLabelHeight - 2 : d[1] == 0 ? 4 : 0);
      if (d[0] == 0) ax = px - kLabelCharWidth * double(chars) / 2;
      Box box = labelBox(ax, ay, chars, right && d[0] != 0);
      if (box.left < x.pixelLo || box.right > x.pixelHi || box.top < y.pixelHi || box.bottom > y.pixelLo) continue;
      if (std::any_of(taken.begin(), taken.end(), [&](const Box& t) { return t.overlaps(box); })) continue;
      taken.push_back(box);
      return {ax, ay, right && d[0] != 0, radius > 8.0};
    }
  Box box = labelBox(px + 8, py - 8, chars, false);  // nowhere free: beside the point, as before
  taken.push_back(box);
  return {px + 8, py - 8, false, false};
}

struct PlacedPoint {
  double px, py;
  size_t index;
};

std::vector<PlacedPoint> drawablePoints(const PlotSeries& s, const Axis& x, const Axis& y) {
  std::vector<PlacedPoint> points;
  for (size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i)
    if (usable(s.x[i], x.log) && usable(s.y[i], y.log)) points.push_back({x.toPixel(s.x[i]), y.toPixel(s.y[i]), i});
  return points;
}

std::string marker(double px, double py, const char* color, bool emphasised, const std::string& tooltip) {
  std::string title = tooltip.empty() ? "" : "<title>" + escapeXml(tooltip) + "</title>";
  if (emphasised)
    return fmt::format(R"(<circle cx="{:.1f}" cy="{:.1f}" r="7" fill="{}" stroke="#000" stroke-width="1.5">{}</circle>)" "\n", px, py,
                       color, title);
  return fmt::format(R"(<circle cx="{:.1f}" cy="{:.1f}" r="4" fill="#fff" stroke="{}" stroke-width="2">{}</circle>)" "\n", px, py,
                     color, title);
}

void drawSeries(std::string& svg, const PlotSeries& s, const char* color, const Axis& x, const Axis& y) {
  auto points = drawablePoints(s, x, y);
  if (s.lines && points.size() > 1) {
    std::string path;
    for (const auto& p : points) path += fmt::format("{}{:.1f},{:.1f}", path.empty() ? "" : " ", p.px, p.py);
    svg += fmt::format(R"(<polyline points="{}" fill="none" stroke="{}" stroke-width="2"/>)" "\n", path, color);
  }
  for (const auto& p : points) {
    bool emphasised = p.index < s.highlighted.size() && s.highlighted[p.index];
    const std::string& tooltip = p.index < s.tooltips.size() ? s.tooltips[p.index] : std::string();
    if (emphasised || s.markers) svg += marker(p.px, p.py, color, emphasised, tooltip);
  }
}

// Labels after every series' points, so none is placed over a point drawn later.
void drawLabels(std::string& svg, const std::vector<PlotSeries>& series, const Axis& x, const Axis& y) {
  std::vector<Box> taken;
  for (const auto& s : series)
    for (const auto& p : drawablePoints(s, x, y)) taken.push_back({p.px - 7, p.py - 7, p.px + 7, p.py + 7});
  for (const auto& s : series)
    for (const auto& p : drawablePoints(s, x, y)) {
      if (p.index >= s.labels.size() || s.labels[p.index].empty()) continue;
      const std::string& label = s.labels[p.index];
      LabelSpot spot = placeLabel(p.px, p.py, label.size(), x, y, taken);
      if (spot.leader) {
        svg += fmt::format(R"(<line x1="{:.1f}" y1="{:.1f}" x2="{:.1f}" y2="{:.1f}" stroke="#999" stroke-width="0.8"/>)" "\n", p.px, p.py,
                           spot.x, spot.y - 4);
      }
      svg += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" font-size="11" fill="#222"{}>{}</text>)" "\n", spot.x, spot.y,
                         spot.rightAligned ? R"( text-anchor="end")" : "", escapeXml(label));
    }
}

constexpr double kLegendCharWidth = 7.0, kLegendFirstRowY = 44, kLegendRowHeight = 16;

struct LegendEntry {
  std::string name;
  bool line = false;
  bool marker = false;
  bool highlight = false;
  const char* color = "#000";
};

std::vector<LegendEntry> legendEntries(const std::vector<PlotSeries>& series) {
  std::vector<LegendEntry> entries;
  // Each entry is drawn as its points are: a line for a connected series, its open marker, and the
  // filled marker of highlighted points in the colour of the series that has them.
  for (size_t i = 0; i < series.size(); ++i)
    entries.push_back({series[i].name, series[i].lines, series[i].markers, false, kPalette[i % std::size(kPalette)]});
  for (size_t i = 0; i < series.size(); ++i) {
    const auto& h = series[i].highlighted;
    if (std::find(h.begin(), h.end(), true) == h.end()) continue;
    entries.push_back({"Pareto-optimal", false, false, true, kPalette[i % std::size(kPalette)]});
    break;
  }
  return entries;
}

double legendEntryWidth(const LegendEntry& e) { return 26 + kLegendCharWidth * double(e.name.size()) + 18; }

// Rows between the title and the plot, so the legend never hides a point: a swatch and a name
// per series (then the highlighted-point marker), wrapping onto a new row at the plot's width.
struct LegendLayout {
  std::vector<std::pair<double, double>> positions;  // (left, row y) of each entry
  int rows = 1;
};

LegendLayout layoutLegend(const std::vector<LegendEntry>& entries, const Axis& x) {
  LegendLayout layout;
  double left = x.pixelLo, rowY = kLegendFirstRowY;
  for (const auto& e : entries) {
    if (left > x.pixelLo && left + legendEntryWidth(e) > x.pixelHi) {
      left = x.pixelLo;
      rowY += kLegendRowHeight;
      ++layout.rows;
    }
    layout.positions.emplace_back(left, rowY);
    left += legendEntryWidth(e);
  }
  return layout;
}

void drawLegend(std::string& svg, const std::vector<LegendEntry>& entries, const LegendLayout& layout) {
  for (size_t k = 0; k < entries.size(); ++k) {
    const LegendEntry& e = entries[k];
    auto [left, rowY] = layout.positions[k];
    if (e.line)
      svg += fmt::format(R"(<line x1="{:.1f}" y1="{:.1f}" x2="{:.1f}" y2="{:.1f}" stroke="{}" stroke-width="2"/>)" "\n",
                         left, rowY, left + 20, rowY, e.color);
    if (e.marker || e.highlight) svg += marker(left + 10, rowY, e.color, e.highlight, "");
    svg += fmt::format(R"(<text x="{:.1f}" y="{:.1f}">{}</text>)" "\n", left + 26, rowY + 4, escapeXml(e.name));
  }
}

constexpr double kKeyRowHeight = 15;

// The key under the x-axis label, in as many columns as the widest line allows.
void drawKey(std::string& svg, const std::vector<std::string>& key, double left, double right, double top) {
  size_t widest = 1;
  for (const auto& line : key) widest = std::max(widest, line.size());
  double columnWidth = kLabelCharWidth * double(widest) + 16;
  size_t columns = std::max<size_t>(1, size_t((right - left) / columnWidth));
  for (size_t i = 0; i < key.size(); ++i)
    svg += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" font-size="11">{}</text>)" "\n", left + columnWidth * double(i % columns),
                       top + kKeyRowHeight * double(i / columns), escapeXml(key[i]));
}

size_t keyRows(const std::vector<std::string>& key, double left, double right) {
  size_t widest = 1;
  for (const auto& line : key) widest = std::max(widest, line.size());
  size_t columns = std::max<size_t>(1, size_t((right - left) / (kLabelCharWidth * double(widest) + 16)));
  return (key.size() + columns - 1) / columns;
}

}  // namespace

std::string svgPlot(const std::vector<PlotSeries>& series, const PlotOptions& options) {
  double width = std::max(options.width, 200), height = std::max(options.height, 150);
  Axis x{options.logX}, y{options.logY};
  std::tie(x.lo, x.hi) = dataRange(series, true, options.logX, options.logY);
  std::tie(y.lo, y.hi) = dataRange(series, false, options.logY, options.logX);
  x.pixelLo = kMarginLeft;
  x.pixelHi = width - kMarginRight;
  double keyHeight = kKeyRowHeight * double(keyRows(options.key, x.pixelLo, x.pixelHi));
  height += keyHeight;  // the key adds rows under the plot; the plot keeps its size
  y.pixelLo = height - kMarginBottom - keyHeight;  // y grows upward: low values at the bottom
  auto legend = legendEntries(series);
  auto legendLayout = layoutLegend(legend, x);
  y.pixelHi = kMarginTop + kLegendRowHeight * double(legendLayout.rows - 1);

  std::string svg = fmt::format(
      R"(<svg xmlns="http://www.w3.org/2000/svg" width="{0}" height="{1}" viewBox="0 0 {0} {1}" font-family="sans-serif" font-size="12">)" "\n",
      width, height);
  svg += fmt::format(R"(<rect width="{}" height="{}" fill="#fff"/>)" "\n", width, height);
  drawAxes(svg, x, y, options);
  drawVerticalMarkers(svg, x, y, options);
  for (size_t i = 0; i < series.size(); ++i) drawSeries(svg, series[i], kPalette[i % std::size(kPalette)], x, y);
  drawLabels(svg, series, x, y);
  drawLegend(svg, legend, legendLayout);
  drawKey(svg, options.key, x.pixelLo, x.pixelHi, y.pixelLo + 58);
  svg += "</svg>\n";
  return svg;
}

std::string escapeXml(std::string_view raw) {
  const std::string text = printable(raw, true);  // XML 1.0 cannot hold other control characters at all
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

}  // namespace aor
