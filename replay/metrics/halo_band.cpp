#include "metrics/halo_band.h"

#include <algorithm>
#include <cmath>

namespace aor {
namespace {

bool farther(float behind, float front, float jump) { return front > 0.0f && behind > front * (1.0f + jump); }

std::vector<uint8_t> silhouettePixels(const std::vector<float>& d, int w, int h, float jump) {
  std::vector<uint8_t> edge(d.size(), 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      size_t i = size_t(y) * w + x;
      float here = d[i];
      if (here <= 0.0f) continue;
      // A sky neighbour is farther than anything.
      auto behindIt = [&](int nx, int ny) {
        if (nx < 0 || ny < 0 || nx >= w || ny >= h) return false;
        float there = d[size_t(ny) * w + nx];
        return there <= 0.0f || farther(there, here, jump);
      };
      edge[i] = behindIt(x - 1, y) || behindIt(x + 1, y) || behindIt(x, y - 1) || behindIt(x, y + 1);
    }
  return edge;
}

// Summed-area table of the silhouette flags: whether a window holds any silhouette pixel in O(1),
// so only windows near a silhouette are searched (most of an image is not).
struct EdgeCounts {
  int w = 0;
  std::vector<uint32_t> sums;  // (w + 1) x (h + 1)
  EdgeCounts(const std::vector<uint8_t>& edge, int width, int height) : w(width), sums(size_t(width + 1) * (height + 1), 0) {
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        at(x + 1, y + 1) = edge[size_t(y) * width + x] + at(x, y + 1) + at(x + 1, y) - at(x, y);
  }
  uint32_t& at(int x, int y) { return sums[size_t(y) * (w + 1) + x]; }
  uint32_t inWindow(int x0, int y0, int x1, int y1) { return at(x1 + 1, y1 + 1) - at(x0, y1 + 1) - at(x1 + 1, y0) + at(x0, y0); }
};

}  // namespace

std::vector<uint8_t> haloBandMask(const std::vector<float>& d, int w, int h, const HaloBandOptions& o) {
  std::vector<uint8_t> edge = silhouettePixels(d, w, h, o.jump);
  EdgeCounts counts(edge, w, h);
  std::vector<uint8_t> band(d.size(), 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float here = d[size_t(y) * w + x];
      if (here <= 0.0f) continue;
      int reach = std::clamp(int(std::ceil(o.pixelsPerUnit * o.radius / here)), 1, o.maxBandPixels);
      const int x0 = std::max(0, x - reach), x1 = std::min(w - 1, x + reach);
      const int y0 = std::max(0, y - reach), y1 = std::min(h - 1, y + reach);
      if (counts.inWindow(x0, y0, x1, y1) == 0) continue;
      bool inBand = false;
      for (int ny = y0; ny <= y1 && !inBand; ++ny)
        for (int nx = x0; nx <= x1 && !inBand; ++nx) {
          size_t j = size_t(ny) * w + nx;
          inBand = edge[j] && farther(here, d[j], o.jump);
        }
      band[size_t(y) * w + x] = inBand;
    }
  return band;
}

MaskedError maskedError(const float* output, const float* reference, const std::vector<uint8_t>& mask) {
  MaskedError e;
  double squared = 0, sum = 0;
  for (size_t i = 0; i < mask.size(); ++i) {
    if (!mask[i]) continue;
    double diff = double(output[i]) - double(reference[i]);
    squared += diff * diff;
    sum += diff;
    ++e.pixels;
  }
  if (e.pixels > 0) {
    e.rmse = std::sqrt(squared / double(e.pixels));
    e.bias = sum / double(e.pixels);
  }
  return e;
}

}  // namespace aor
