#include "metrics/flip.h"

#include <algorithm>
#include <cmath>

namespace aor {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The paper's constants: colour-error exponent and its remapping knee, feature-error exponent,
// feature-detector width in degrees.
constexpr double kColorExponent = 0.7, kKneeFraction = 0.4, kKneeValue = 0.95;
constexpr double kFeatureExponent = 0.5, kFeatureWidthDegrees = 0.082;
// Achromatic contrast sensitivity as a Gaussian in the spatial domain (amplitude 1, scale b); the
// filter's radius follows the largest scale of all three channels, as the paper's does.
constexpr double kLuminanceScale = 0.0047, kLargestScale = 0.04;

// sRGB primaries (IEC 61966-2-1) to CIE XYZ, D65 white.
constexpr double kRgbToXyz[3][3] = {{0.4123908, 0.3575843, 0.1804808},
                                    {0.2126390, 0.7151687, 0.0721923},
                                    {0.0193308, 0.1191948, 0.9505322}};

struct Lab {
  double L, a, b;
};

double labCurve(double t) {
  constexpr double d = 6.0 / 29.0;
  return t > d * d * d ? std::cbrt(t) : t / (3 * d * d) + 4.0 / 29.0;
}

// CIELAB of linear RGB, then the Hunt adjustment (chroma scaled by 0.01 L) the paper applies.
Lab huntLab(double r, double g, double b) {
  double xyz[3];
  for (int i = 0; i < 3; ++i) xyz[i] = kRgbToXyz[i][0] * r + kRgbToXyz[i][1] * g + kRgbToXyz[i][2] * b;
  double white[3];
  for (int i = 0; i < 3; ++i) white[i] = kRgbToXyz[i][0] + kRgbToXyz[i][1] + kRgbToXyz[i][2];
  double fx = labCurve(xyz[0] / white[0]), fy = labCurve(xyz[1] / white[1]), fz = labCurve(xyz[2] / white[2]);
  double L = 116 * fy - 16;
  return {L, 0.01 * L * 500 * (fx - fy), 0.01 * L * 200 * (fy - fz)};
}

double hyab(const Lab& p, const Lab& q) { return std::abs(p.L - q.L) + std::hypot(p.a - q.a, p.b - q.b); }

// The largest colour difference the remapping is scaled by: pure green against pure blue.
double maxColorDifference() { return std::pow(hyab(huntLab(0, 1, 0), huntLab(0, 0, 1)), kColorExponent); }

double greyLightness(double y) { return 116 * labCurve(std::clamp(y, 0.0, 1.0)) - 16; }

// One-dimensional kernels, applied along x then y with clamped borders.
using Kernel = std::vector<double>;

Kernel luminanceCsfKernel(double ppd) {
  int radius = int(std::ceil(3 * std::sqrt(kLargestScale / (2 * kPi * kPi)) * ppd));
  Kernel k(size_t(2 * radius + 1));
  double sum = 0;
  for (int i = -radius; i <= radius; ++i) {
    double x = i / ppd;  // degrees
    k[size_t(i + radius)] = std::sqrt(kPi / kLuminanceScale) * std::exp(-kPi * kPi * x * x / kLuminanceScale);
    sum += k[size_t(i + radius)];
  }
  for (double& w : k) w /= sum;
  return k;
}

// Gaussian, its first and its second derivative; each derivative's positive and negative weights
// are scaled to sum to +1 and -1, the Gaussian to 1.
struct FeatureKernels {
  Kernel gauss, first, second;
};

FeatureKernels featureKernels(double ppd) {
  double sigma = 0.5 * kFeatureWidthDegrees * ppd;
  int radius = int(std::ceil(3 * sigma));
  FeatureKernels f{Kernel(size_t(2 * radius + 1)), Kernel(size_t(2 * radius + 1)), Kernel(size_t(2 * radius + 1))};
  double gSum = 0, firstPos = 0, firstNeg = 0, secondPos = 0, secondNeg = 0;
  for (int i = -radius; i <= radius; ++i) {
    size_t j = size_t(i + radius);
    double g = std::exp(-double(i * i) / (2 * sigma * sigma));
    f.gauss[j] = g;
    f.first[j] = -double(i) * g;
    f.second[j] = (double(i * i) / (sigma * sigma) - 1) * g;
    gSum += g;
    (f.first[j] > 0 ? firstPos : firstNeg) += std::abs(f.first[j]);
    (f.second[j] > 0 ? secondPos : secondNeg) += std::abs(f.second[j]);
  }
  for (size_t j = 0; j < f.gauss.size(); ++j) {
    f.gauss[j] /= gSum;
    f.first[j] /= f.first[j] > 0 ? firstPos : firstNeg;
    f.second[j] /= f.second[j] > 0 ? secondPos : secondNeg;
  }
  return f;
}

struct Image {
  int width, height;
  std::vector<double> v;
  double at(int x, int y) const { return v[size_t(std::clamp(y, 0, height - 1)) * size_t(width) + size_t(std::clamp(x, 0, width - 1))]; }
};

Image convolve(const Image& in, const Kernel& k, bool alongX) {
  Image out{in.width, in.height, std::vector<double>(in.v.size())};
  int r = int(k.size() / 2);
  for (int y = 0; y < in.height; ++y)
    for (int x = 0; x < in.width; ++x) {
      double sum = 0;
      for (int i = -r; i <= r; ++i) sum += k[size_t(i + r)] * (alongX ? in.at(x + i, y) : in.at(x, y + i));
      out.v[size_t(y) * size_t(in.width) + size_t(x)] = sum;
    }
  return out;
}

Image separable(const Image& in, const Kernel& kx, const Kernel& ky) { return convolve(convolve(in, kx, true), ky, false); }

// Edge and point strength per pixel: gradient magnitudes of the first and second derivatives.
void features(const Image& y, const FeatureKernels& f, std::vector<double>& edges, std::vector<double>& points) {
  Image dx = separable(y, f.first, f.gauss), dy = separable(y, f.gauss, f.first);
  Image ddx = separable(y, f.second, f.gauss), ddy = separable(y, f.gauss, f.second);
  edges.resize(y.v.size());
  points.resize(y.v.size());
  for (size_t i = 0; i < y.v.size(); ++i) {
    edges[i] = std::hypot(dx.v[i], dy.v[i]);
    points[i] = std::hypot(ddx.v[i], ddy.v[i]);
  }
}

Image clampedImage(const float* values, int width, int height) {
  Image image{width, height, std::vector<double>(size_t(width) * size_t(height))};
  for (size_t i = 0; i < image.v.size(); ++i) image.v[i] = std::isfinite(values[i]) ? std::clamp(double(values[i]), 0.0, 1.0) : 0.0;
  return image;
}

// The colour error's remapping: [0, knee] to [0, 0.95] linearly, the rest to (0.95, 1].
double remapColorError(double difference, double cmax) {
  double e = std::pow(difference, kColorExponent), knee = kKneeFraction * cmax;
  return e < knee ? e * kKneeValue / knee : kKneeValue + (e - knee) / (cmax - knee) * (1 - kKneeValue);
}

}  // namespace

std::vector<float> flipErrorMap(const float* reference, const float* test, int width, int height, const FlipOptions& options) {
  const double ppd = options.pixelsPerDegree, cmax = maxColorDifference();
  Image ref = clampedImage(reference, width, height), tst = clampedImage(test, width, height);
  Kernel csf = luminanceCsfKernel(ppd);
  Image refFiltered = separable(ref, csf, csf), tstFiltered = separable(tst, csf, csf);
  FeatureKernels fk = featureKernels(ppd);
  std::vector<double> refEdges, refPoints, tstEdges, tstPoints;
  features(ref, fk, refEdges, refPoints);
  features(tst, fk, tstEdges, tstPoints);
  std::vector<float> out(ref.v.size());
  for (size_t i = 0; i < out.size(); ++i) {
    double color = remapColorError(std::abs(greyLightness(refFiltered.v[i]) - greyLightness(tstFiltered.v[i])), cmax);
    double feature = std::pow(std::max(std::abs(refEdges[i] - tstEdges[i]), std::abs(refPoints[i] - tstPoints[i])) / std::sqrt(2.0),
                              kFeatureExponent);
    out[i] = float(std::pow(color, 1 - feature));
  }
  return out;
}

double meanFlip(const float* reference, const float* test, const uint8_t* mask, int width, int height, const FlipOptions& options) {
  std::vector<float> map = flipErrorMap(reference, test, width, height, options);
  double sum = 0;
  int64_t count = 0;
  for (size_t i = 0; i < map.size(); ++i)
    if (!mask || mask[i]) {
      sum += map[i];
      ++count;
    }
  return count ? sum / double(count) : 0.0;
}

}  // namespace aor
