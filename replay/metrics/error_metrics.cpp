#include "metrics/error_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "metrics/depth.h"
#include "metrics/flip.h"
#include "metrics/halo_band.h"
#include "core/percentile.h"

namespace aor {
namespace {

constexpr int kSsimRadius = 5;  // 11x11 window
constexpr double kSsimSigma = 1.5;
constexpr double kSsimC1 = 0.01 * 0.01;  // (K1 L)^2 with L = 1
constexpr double kSsimC2 = 0.03 * 0.03;  // (K2 L)^2

std::vector<double> gaussianKernel() {
  std::vector<double> k(2 * kSsimRadius + 1);
  for (int i = -kSsimRadius; i <= kSsimRadius; ++i) k[size_t(i + kSsimRadius)] = std::exp(-0.5 * i * i / (kSsimSigma * kSsimSigma));
  return k;  // unnormalised: every use divides by the blurred mask
}

// Separable Gaussian blur with the window truncated at the image border.
std::vector<double> blur(const std::vector<double>& image, int width, int height) {
  static const std::vector<double> kernel = gaussianKernel();
  std::vector<double> rows(image.size(), 0.0), out(image.size(), 0.0);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      double sum = 0;
      for (int d = -kSsimRadius; d <= kSsimRadius; ++d)
        if (x + d >= 0 && x + d < width) sum += kernel[size_t(d + kSsimRadius)] * image[size_t(y) * size_t(width) + size_t(x + d)];
      rows[size_t(y) * size_t(width) + size_t(x)] = sum;
    }
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      double sum = 0;
      for (int d = -kSsimRadius; d <= kSsimRadius; ++d)
        if (y + d >= 0 && y + d < height) sum += kernel[size_t(d + kSsimRadius)] * rows[size_t(y + d) * size_t(width) + size_t(x)];
      out[size_t(y) * size_t(width) + size_t(x)] = sum;
    }
  return out;
}

double psnrFromMse(double mse) { return mse > 0 ? 10.0 * std::log10(1.0 / mse) : std::numeric_limits<double>::infinity(); }

nlohmann::json finiteOrNull(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json minMeanMax(const std::vector<double>& values) {
  double lo = *std::min_element(values.begin(), values.end()), hi = *std::max_element(values.begin(), values.end());
  double mean = 0;
  for (double v : values) mean += v / double(values.size());
  return {{"min", lo}, {"mean", mean}, {"max", hi}};
}

bool isSkyDepth(float depth, bool reversedDepth) {
  if (!std::isfinite(depth)) return true;  // invalid depth cannot be compared either
  return reversedDepth ? depth <= 0.0f : depth >= 1.0f;
}

// Masked Gaussian-window SSIM (error_metrics.h); `mask` nonzero = compared. 1 when nothing is compared.
double maskedSsim(const float* a, const float* b, const uint8_t* mask, int width, int height) {
  size_t n = size_t(width) * size_t(height);
  std::vector<double> m(n), ma(n), mb(n), maa(n), mbb(n), mab(n);
  for (size_t i = 0; i < n; ++i) {
    double w = mask[i] ? 1.0 : 0.0, x = mask[i] ? a[i] : 0.0, y = mask[i] ? b[i] : 0.0;
    m[i] = w;
    ma[i] = x;
    mb[i] = y;
    maa[i] = x * x;
    mbb[i] = y * y;
    mab[i] = x * y;
  }
  auto W = blur(m, width, height), A = blur(ma, width, height), B = blur(mb, width, height);
  auto AA = blur(maa, width, height), BB = blur(mbb, width, height), AB = blur(mab, width, height);
  double sum = 0;
  int64_t count = 0;
  for (size_t i = 0; i < n; ++i) {
    if (!mask[i]) continue;
    double muA = A[i] / W[i], muB = B[i] / W[i];
    double varA = std::max(0.0, AA[i] / W[i] - muA * muA), varB = std::max(0.0, BB[i] / W[i] - muB * muB);
    double cov = AB[i] / W[i] - muA * muB;
    sum += ((2 * muA * muB + kSsimC1) * (2 * cov + kSsimC2)) / ((muA * muA + muB * muB + kSsimC1) * (varA + varB + kSsimC2));
    ++count;
  }
  return count ? sum / double(count) : 1.0;
}

}  // namespace

ErrorMetrics computeErrorMetrics(const float* output, const float* reference, const float* depth, int width, int height,
                                 bool reversedDepth, bool withFlip) {
  size_t n = size_t(width) * size_t(height);
  std::vector<uint8_t> mask(n);
  std::vector<double> absErrors;
  absErrors.reserve(n);
  ErrorMetrics m;
  for (size_t i = 0; i < n; ++i) {
    mask[i] = depth == nullptr || !isSkyDepth(depth[i], reversedDepth);
    if (!mask[i]) continue;
    double e = double(output[i]) - double(reference[i]);
    m.sumSquared += e * e;
    m.sumAbsolute += std::abs(e);
    m.sumSigned += e;
    m.maxError = std::max(m.maxError, std::abs(e));
    absErrors.push_back(std::abs(e));
  }
  m.pixels = int64_t(absErrors.size());
  if (m.pixels == 0) return m;
  double count = double(m.pixels);
  m.rmse = std::sqrt(m.sumSquared / count);
  m.mae = m.sumAbsolute / count;
  m.bias = m.sumSigned / count;
  m.psnr = psnrFromMse(m.sumSquared / count);
  m.ssim = maskedSsim(output, reference, mask.data(), width, height);
  m.p99 = nearestRankPercentile(std::move(absErrors), 0.99);
  if (withFlip) m.flip = meanFlip(reference, output, mask.data(), width, height);
  return m;
}

BandError bandError(const float* output, const float* reference, const float* depth, int width, int height,
                    const glm::mat4& projection, double radius) {
  const size_t n = size_t(width) * size_t(height);
  HaloBandOptions options;
  options.radius = float(radius);
  options.pixelsPerUnit = std::abs(projection[0][0]) * float(width) * 0.5f;
  const auto band = haloBandMask(linearViewDistances({depth, n}, projection), width, height, options);
  const MaskedError e = maskedError(output, reference, band);
  return {e.pixels, e.rmse, e.bias, e.rmse * e.rmse * double(e.pixels), e.bias * double(e.pixels), radius};
}

namespace {

nlohmann::json bandJson(const BandError& b) {
  return {{"pixels", b.pixels}, {"rmse", b.rmse}, {"bias", b.bias}, {"radius", b.radius}};
}

}  // namespace

nlohmann::json toJson(const ErrorMetrics& m) {
  nlohmann::json j{{"pixels", m.pixels}, {"rmse", m.rmse}, {"mae", m.mae},   {"max", m.maxError},
                   {"bias", m.bias},     {"psnr", finiteOrNull(m.psnr)}, {"ssim", m.ssim}, {"p99", m.p99}};
  if (m.flip) j["flip"] = *m.flip;
  j["halo_band"] = bandJson(m.haloBand);
  return j;
}

void ErrorAnalysis::addFrame(const AnalyzedFrame& frame) {
  if (!frame.reference || !frame.visibility) return;
  ErrorMetrics& m = frames_[frame.index] = computeErrorMetrics(
      frame.visibility, frame.reference->data(), frame.depth, frame.width, frame.height, isReversedDepth(frame.projection),
      withFlip_);
  if (frame.depth)
    m.haloBand = bandError(frame.visibility, frame.reference->data(), frame.depth, frame.width, frame.height,
                           frame.projection, frame.bandRadius);
}

nlohmann::json ErrorAnalysis::frameJson(int index) const {
  auto it = frames_.find(index);
  return it == frames_.end() ? nlohmann::json(nullptr) : toJson(it->second);
}

nlohmann::json ErrorAnalysis::summaryJson() const {
  if (frames_.empty()) return nullptr;
  ErrorMetrics pooled;
  std::vector<double> rmse, ssim;
  double p99Sum = 0, flipSum = 0;
  for (const auto& [index, m] : frames_) {
    flipSum += m.flip.value_or(0.0) * double(m.pixels);
    pooled.pixels += m.pixels;
    pooled.sumSquared += m.sumSquared;
    pooled.sumAbsolute += m.sumAbsolute;
    pooled.sumSigned += m.sumSigned;
    pooled.maxError = std::max(pooled.maxError, m.maxError);
    pooled.haloBand.pixels += m.haloBand.pixels;
    pooled.haloBand.sumSquared += m.haloBand.sumSquared;
    pooled.haloBand.sumSigned += m.haloBand.sumSigned;
    pooled.haloBand.radius = m.haloBand.radius;
    rmse.push_back(m.rmse);
    ssim.push_back(m.ssim);
    p99Sum += m.p99;
  }
  double count = std::max(1.0, double(pooled.pixels));
  pooled.rmse = std::sqrt(pooled.sumSquared / count);
  pooled.mae = pooled.sumAbsolute / count;
  pooled.bias = pooled.sumSigned / count;
  pooled.psnr = pooled.pixels ? psnrFromMse(pooled.sumSquared / count) : 0.0;
  pooled.ssim = 0;
  for (double s : ssim) pooled.ssim += s / double(ssim.size());
  pooled.p99 = p99Sum / double(frames_.size());
  if (withFlip_) pooled.flip = flipSum / count;
  const double band = std::max<double>(1.0, double(pooled.haloBand.pixels));
  pooled.haloBand.rmse = std::sqrt(pooled.haloBand.sumSquared / band);
  pooled.haloBand.bias = pooled.haloBand.sumSigned / band;
  auto j = toJson(pooled);
  j["reference"] = referenceKind_;
  j["frames"] = frames_.size();
  j["rmse_over_frames"] = minMeanMax(rmse);
  j["ssim_over_frames"] = minMeanMax(ssim);
  return j;
}

}  // namespace aor
