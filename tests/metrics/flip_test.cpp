// LDR-FLIP of grey images (metrics/flip.h).
#include "metrics/flip.h"

#include <cmath>

#include <gtest/gtest.h>

namespace aor {
namespace {

float srgbToLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

// A smooth 8-bit pattern and the same with a dark 10x10 square, as linear values the way NVIDIA's
// FLIP tool reads 8-bit PNGs (sRGB decoded).
struct Pair {
  int width = 64, height = 48;
  std::vector<float> reference, test;
  Pair() : reference(size_t(width * height)), test(size_t(width * height)) {
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        int r = 128 + int(std::lround(100 * std::sin(0.3 * x) * std::cos(0.2 * y)));
        int t = (x >= 20 && x < 30 && y >= 10 && y < 20) ? 40 : r;
        reference[size_t(y * width + x)] = srgbToLinear(float(r) / 255.f);
        test[size_t(y * width + x)] = srgbToLinear(float(t) / 255.f);
      }
  }
};

// NVIDIA's FLIP tool (github.com/NVlabs/flip, src/cpp, built in a scratch folder) on these two
// images written as 8-bit grey PNGs: `flip -r ref.png -t test.png` prints "Mean: 0.016076".
TEST(Flip, MatchesNvidiasToolOnASyntheticPair) {
  Pair p;
  EXPECT_NEAR(meanFlip(p.reference.data(), p.test.data(), nullptr, p.width, p.height), 0.016076, 2e-6);
}

TEST(Flip, IdenticalImagesHaveNoError) {
  Pair p;
  auto map = flipErrorMap(p.reference.data(), p.reference.data(), p.width, p.height);
  for (float e : map) EXPECT_EQ(e, 0.0f);
}

TEST(Flip, TheErrorSitsWhereTheImagesDiffer) {
  Pair p;
  auto map = flipErrorMap(p.reference.data(), p.test.data(), p.width, p.height);
  EXPECT_GT(map[size_t(15 * p.width + 25)], 0.1f);  // inside the square
  EXPECT_LT(map[size_t(40 * p.width + 55)], 1e-3f);  // far from it
  for (float e : map) {
    EXPECT_GE(e, 0.0f);
    EXPECT_LE(e, 1.0f);
  }
}

TEST(Flip, TheMaskChoosesThePixelsAveraged) {
  Pair p;
  std::vector<uint8_t> square(p.reference.size(), 0), none(p.reference.size(), 0);
  for (int y = 10; y < 20; ++y)
    for (int x = 20; x < 30; ++x) square[size_t(y * p.width + x)] = 1;
  double all = meanFlip(p.reference.data(), p.test.data(), nullptr, p.width, p.height);
  double inside = meanFlip(p.reference.data(), p.test.data(), square.data(), p.width, p.height);
  EXPECT_GT(inside, 10 * all);
  EXPECT_EQ(meanFlip(p.reference.data(), p.test.data(), none.data(), p.width, p.height), 0.0);
}

}  // namespace
}  // namespace aor
