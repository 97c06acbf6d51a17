#include "report/html/frame_images.h"

#include <algorithm>
#include <cmath>
#include <set>

#include <fmt/format.h>

#include "capture/image_io.h"
#include "report/html/charts.h"
#include "report/html/colour_map.h"
#include "report/html/html_page.h"

namespace aor::html {
namespace {

constexpr int kShownWidth = 300;  // four a row on a 1280-pixel page  // CSS pixels per image: small captures are scaled up, pixelated

bool isSky(const FrameImages& f, size_t i) { return i < f.sky.size() && f.sky[i]; }

// The 99th percentile of |values| over non-sky pixels: a scale that a few outliers do not flatten.
double robustMax(const FrameImages& f, const std::vector<float>& values) {
  std::vector<float> magnitudes;
  for (size_t i = 0; i < values.size(); ++i)
    if (!isSky(f, i) && std::isfinite(values[i])) magnitudes.push_back(std::abs(values[i]));
  if (magnitudes.empty()) return 0;
  size_t k = std::min(magnitudes.size() - 1, size_t(0.99 * double(magnitudes.size())));
  std::nth_element(magnitudes.begin(), magnitudes.begin() + long(k), magnitudes.end());
  return magnitudes[k];
}

std::vector<float> difference(const std::vector<float>& a, const std::vector<float>& b) {
  std::vector<float> d(a.size());
  for (size_t i = 0; i < a.size(); ++i) d[i] = a[i] - b[i];
  return d;
}

// RGB planes (interleaved) of values mapped through a scale; sky is mid grey.
std::string colourPng(const FrameImages& f, const std::vector<float>& values, double scale, bool diverging) {
  std::vector<float> rgb(values.size() * 3);
  for (size_t i = 0; i < values.size(); ++i) {
    Rgb c = isSky(f, i) ? Rgb{0.5f, 0.5f, 0.5f}
            : diverging  ? divergingColour(double(values[i]) / scale)
                         : sequentialColour(std::abs(double(values[i])) / scale);
    std::copy(c.begin(), c.end(), rgb.begin() + long(3 * i));
  }
  return encodePng(f.width, f.height, 3, rgb.data());
}

std::string figure(const std::string& png, int width, int height, const std::string& caption) {
  int shownHeight = int(std::lround(double(kShownWidth) * height / std::max(1, width)));
  return fmt::format("<figure><img src=\"{}\" width=\"{}\" height=\"{}\" alt=\"{}\"><figcaption>{}</figcaption></figure>\n",
                     pngDataUri(png), kShownWidth, shownHeight, escape(caption), escape(caption));
}

}  // namespace

std::vector<int> framesToShow(int begin, int end, int count) {
  std::set<int> chosen;
  int first = end - begin > 1 ? begin + 1 : begin;
  int span = end - 1 - first;
  for (int k = 0; k < count; ++k) chosen.insert(count == 1 || span <= 0 ? first : first + span * k / (count - 1));
  return {chosen.begin(), chosen.end()};
}

std::string frameImagesHtml(const std::vector<FrameImages>& frames) {
  double errorScale = 0, changeScale = 0;
  for (const auto& f : frames) {
    if (f.reference) errorScale = std::max(errorScale, robustMax(f, difference(f.ao, *f.reference)));
    if (!f.previousAo.empty()) changeScale = std::max(changeScale, robustMax(f, difference(f.ao, f.previousAo)));
  }
  errorScale = niceCeiling(errorScale);
  changeScale = niceCeiling(changeScale);
  std::string html;
  for (const auto& f : frames) {
    html += fmt::format("<div class=\"frame-row\" data-frame=\"{}\">\n<h3>frame {}</h3>\n", f.index, f.index);
    html += figure(encodePng(f.width, f.height, 1, f.ao.data()), f.width, f.height, fmt::format("AO, frame {}", f.index));
    if (f.reference) {
      html += figure(encodePng(f.width, f.height, 1, f.reference->data()), f.width, f.height, "reference (ray traced)");
      html += figure(colourPng(f, difference(f.ao, *f.reference), errorScale, false), f.width, f.height,
                     "|AO - reference| (heat map, scale below; sky grey)");
    }
    if (!f.previousAo.empty())
      html += figure(colourPng(f, difference(f.ao, f.previousAo), changeScale, true), f.width, f.height,
                     fmt::format("AO frame {} - frame {} (flicker; not reprojected, so camera motion shows too)", f.index, f.index - 1));
    html += "</div>\n";
  }
  bool anyReference = std::any_of(frames.begin(), frames.end(), [](const auto& f) { return f.reference.has_value(); });
  bool anyPrevious = std::any_of(frames.begin(), frames.end(), [](const auto& f) { return !f.previousAo.empty(); });
  html += "<div class=\"scales\">";
  if (anyReference) html += colourScaleSvg("|AO - reference| (visibility)", 0, errorScale, false);
  if (anyPrevious) html += colourScaleSvg("AO(frame) - AO(frame - 1) (visibility)", -changeScale, changeScale, true);
  if (!anyReference) html += "<p class=\"note\">The capture has no reference for these frames: no error image.</p>";
  return html + "</div>\n";
}

}  // namespace aor::html
