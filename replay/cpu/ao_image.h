#pragma once
// A GTAO pass output computed on the CPU: float for the mirror of the shader (gtao_cpu.h), double
// for the precision model (gtao_double.h).
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

namespace aor {

template <class T>
struct AoImage {
  int width = 0, height = 0;
  std::vector<T> visibility;
  std::vector<glm::vec<3, T>> bent;  // view space; empty with bent=0
};

using CpuAoImage = AoImage<float>;
using DoubleAoImage = AoImage<double>;

// Fills an image pixel by pixel in row order: `pixel(glm::ivec2, glm::vec<3, T>& bent)` returns the
// visibility and writes the bent normal, which is kept only when `withBent`.
template <class T, class PixelFunction>
AoImage<T> computeAoImage(int width, int height, bool withBent, PixelFunction&& pixel) {
  size_t pixels = size_t(width) * size_t(height);
  AoImage<T> out;
  out.width = width;
  out.height = height;
  out.visibility.resize(pixels);
  if (withBent) out.bent.resize(pixels);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      size_t i = size_t(y) * size_t(width) + size_t(x);
      glm::vec<3, T> bent;
      out.visibility[i] = pixel(glm::ivec2(x, y), bent);
      if (withBent) out.bent[i] = bent;
    }
  return out;
}

}  // namespace aor
