#pragma once
// Splits an image's rows into contiguous bands and runs `fn(firstRow, endRow)` on each, one band per
// hardware thread (the calling thread takes the last). Only for per-pixel maps: every pixel is
// written by exactly one band, so the result does not depend on the number of bands; sums go
// through rowOrderedMean.
#include <algorithm>
#include <future>
#include <thread>
#include <vector>

namespace aor {

template <class Fn>
void forEachRowBand(int height, Fn&& fn) {
  int bands = std::clamp(int(std::thread::hardware_concurrency()), 1, std::max(1, height));
  std::vector<std::future<void>> others;
  for (int b = 0; b + 1 < bands; ++b)
    others.push_back(std::async(std::launch::async, [&fn, b, bands, height] { fn(height * b / bands, height * (b + 1) / bands); }));
  fn(height * (bands - 1) / bands, height);
  for (auto& f : others) f.get();
}

// Mean of term(i) over the pixels i where counted(i) (0 when there are none). Each row is summed on
// its own and the row sums are then added in order, so the result does not depend on how the rows
// are split between threads.
template <class Counted, class Term>
double rowOrderedMean(int width, int height, Counted&& counted, Term&& term) {
  std::vector<double> rowSum(size_t(height), 0.0);
  std::vector<size_t> rowCount(size_t(height), 0);
  forEachRowBand(height, [&](int firstRow, int endRow) {
    for (int y = firstRow; y < endRow; ++y) {
      double sum = 0;
      size_t count = 0;
      for (size_t i = size_t(y) * size_t(width), end = i + size_t(width); i < end; ++i) {
        if (!counted(i)) continue;
        sum += term(i);
        ++count;
      }
      rowSum[size_t(y)] = sum;
      rowCount[size_t(y)] = count;
    }
  });
  double sum = 0;
  size_t count = 0;
  for (size_t y = 0; y < size_t(height); ++y) {
    sum += rowSum[y];
    count += rowCount[y];
  }
  return count ? sum / double(count) : 0.0;
}

}  // namespace aor
