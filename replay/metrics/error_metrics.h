#pragma once
// Error of the AO output against a reference visibility (issue "Ground truth"), sky masked.
//
// Per frame, over the pixels that are not sky (sky: depth at the far value, 1 for standard depth
// and 0 for reversed depth, reversed iff projection[3][2] > 0; non-finite depth is masked too),
// with error e = output - reference (visibility, 1 = unoccluded):
//   rmse, mae, max (max |e|), bias (mean signed e: > 0 means the output is too bright/open),
//   psnr (10 log10(1 / mse), peak 1; null when the images are identical),
//   ssim (Wang et al. 2004 with an 11x11 Gaussian window, sigma 1.5, C1 = 0.01^2, C2 = 0.03^2 on
//         visibility in [0,1]; windows use only non-sky pixels (weights renormalised), and the
//         SSIM map is averaged over non-sky pixels),
//   p99 (99th percentile of |e|, nearest rank), pixels (how many were compared),
//   flip (only when asked for: mean LDR-FLIP over the non-sky pixels, metrics/flip.h; the images
//         are filtered whole, sky included, as a viewer sees them),
//   halo_band (pixels, rmse, bias and the radius that built it: the error over the halo band,
//         metrics/halo_band.h, from the capture's scene.ao_radius, else kHaloBandDefaultRadius).
// Summary over frames: rmse, mae, bias and psnr pooled over every compared pixel of every frame,
// max the largest max, ssim and p99 the mean over frames, flip pooled over pixels, plus
// min/mean/max of the per-frame rmse and ssim.
#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "metrics/analyzed_frame.h"
#include "metrics/depth.h"  // isReversedDepth

namespace aor {

// Error over the halo band (metrics/halo_band.h): the background within the AO radius behind a
// nearer silhouette, built from the capture's depth and radius so every technique is judged on the
// same pixels.
struct BandError {
  int64_t pixels = 0;
  double rmse = 0, bias = 0;
  double sumSquared = 0, sumSigned = 0;  // for pooling over frames
  double radius = 0;                     // world units
};

struct ErrorMetrics {
  int64_t pixels = 0;
  double rmse = 0, mae = 0, maxError = 0, bias = 0, psnr = 0, ssim = 1, p99 = 0;
  double sumSquared = 0, sumAbsolute = 0, sumSigned = 0;  // for pooling over frames
  std::optional<double> flip;
  BandError haloBand;
};

// The halo band's error of one frame (`depth` and `projection` give its view distances).
BandError bandError(const float* output, const float* reference, const float* depth, int width, int height,
                    const glm::mat4& projection, double radius);

// `depth` may be null (nothing masked). Pixels with no non-sky neighbour in a window are skipped.
ErrorMetrics computeErrorMetrics(const float* output, const float* reference, const float* depth, int width, int height,
                                 bool reversedDepth, bool withFlip = false);

// What a reference is, as reports name it.
inline constexpr const char* kRayTracedReference = "ray-traced";      // the capture's own
inline constexpr const char* kScreenSpaceReference = "screen-space";  // the reference technique's

class ErrorAnalysis {
 public:
  // `referenceKind` names what the reference is (kRayTracedReference, ...); it is reported.
  explicit ErrorAnalysis(std::string referenceKind = kRayTracedReference, bool withFlip = false)
      : referenceKind_(std::move(referenceKind)), withFlip_(withFlip) {}
  void addFrame(const AnalyzedFrame& frame);
  nlohmann::json frameJson(int index) const;  // null when the frame had no reference
  nlohmann::json summaryJson() const;         // null when no frame had one

 private:
  std::string referenceKind_;
  bool withFlip_ = false;
  std::map<int, ErrorMetrics> frames_;
};

nlohmann::json toJson(const ErrorMetrics& metrics);

}  // namespace aor
