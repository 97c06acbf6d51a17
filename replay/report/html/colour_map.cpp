#include "report/html/colour_map.h"

#include <algorithm>
#include <cmath>
#include <iterator>

#include <fmt/format.h>

namespace aor::html {
namespace {

// Piecewise-linear through evenly spaced stops (approximately matplotlib's "inferno").
constexpr Rgb kSequential[] = {{0.00f, 0.00f, 0.02f}, {0.26f, 0.04f, 0.41f}, {0.58f, 0.15f, 0.40f},
                               {0.87f, 0.32f, 0.23f}, {0.99f, 0.65f, 0.04f}, {0.99f, 1.00f, 0.64f}};
constexpr Rgb kDiverging[] = {{0.02f, 0.19f, 0.38f}, {0.26f, 0.58f, 0.76f}, {0.97f, 0.97f, 0.97f},
                              {0.84f, 0.38f, 0.30f}, {0.40f, 0.00f, 0.12f}};

template <size_t N>
Rgb interpolate(const Rgb (&stops)[N], double t) {
  t = std::clamp(t, 0.0, 1.0) * double(N - 1);
  size_t i = std::min(size_t(t), N - 2);
  float f = float(t - double(i));
  Rgb out;
  for (size_t c = 0; c < 3; ++c) out[c] = stops[i][c] + (stops[i + 1][c] - stops[i][c]) * f;
  return out;
}

}  // namespace

Rgb sequentialColour(double t) { return interpolate(kSequential, std::isfinite(t) ? t : 0.0); }
Rgb divergingColour(double t) { return interpolate(kDiverging, std::isfinite(t) ? (t + 1.0) / 2.0 : 0.5); }

std::string cssColour(const Rgb& c) {
  auto byte = [](float v) { return int(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); };
  return fmt::format("#{:02x}{:02x}{:02x}", byte(c[0]), byte(c[1]), byte(c[2]));
}

}  // namespace aor::html
