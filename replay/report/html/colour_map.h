#pragma once
// Colour scales of the report's images: sequential for |error| (dark = none, bright = most), and
// diverging for signed differences (blue < 0 < red, white at 0). Both stay ordered in lightness,
// so they read in grey print too.
#include <array>
#include <string>

namespace aor::html {

using Rgb = std::array<float, 3>;  // each in [0, 1]

Rgb sequentialColour(double t);  // t in [0, 1], clamped
Rgb divergingColour(double t);   // t in [-1, 1], clamped
std::string cssColour(const Rgb& colour);  // "#rrggbb"

}  // namespace aor::html
