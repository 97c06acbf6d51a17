#pragma once
// Splits an image's rows into contiguous bands and runs `fn(firstRow, endRow)` on each, one band per
// hardware thread (the calling thread takes the last). Only for per-pixel maps: every pixel is
// written by exactly one band, so the result does not depend on the number of bands. Sums stay
// sequential where their order matters for bit-identical reports.
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

}  // namespace aor
