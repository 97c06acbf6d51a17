// Decoding RenderDoc's texel bytes: each depth layout RenderDoc 1.24 returns for Vulkan (lavapipe)
// and OpenGL (llvmpipe), chosen by API and format, and normal encodings, against values worked
// out by hand.
#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include "import/import_problem.h"
#include "import/texel_decoding.h"

namespace aor {
namespace {

template <typename T>
void append(std::vector<uint8_t>& bytes, T v) {
  const auto* p = reinterpret_cast<const uint8_t*>(&v);
  bytes.insert(bytes.end(), p, p + sizeof v);
}

TexelImage image(const char* format, int width, int height, std::vector<uint8_t> bytes, bool bgra = false) {
  return {width, height, format, bgra, std::move(bytes)};
}

TEST(DepthDecoding, UnormTexelsFollowVulkansRule) {
  std::vector<uint8_t> d16;
  for (uint16_t v : {uint16_t(0), uint16_t(32768), uint16_t(65535)}) append(d16, v);
  EXPECT_EQ(decodeDepth(image("D16", 3, 1, d16), "Vulkan"), (std::vector<float>{0.0f, 32768.0f / 65535.0f, 1.0f}));
  EXPECT_EQ(decodeDepth(image("D16", 3, 1, d16), "OpenGL"), (std::vector<float>{0.0f, 32768.0f / 65535.0f, 1.0f}));
  std::vector<uint8_t> d24;  // the top byte (X8) is not depth
  for (uint32_t v : {0xAB000000u, 0x00800000u, 0xFFFFFFFFu}) append(d24, v);
  EXPECT_EQ(decodeDepth(image("D24", 3, 1, d24), "Vulkan"),
            (std::vector<float>{0.0f, 8388608.0f / 16777215.0f, 1.0f}));
}

TEST(DepthDecoding, OpenGLsD24IsTheHigh24BitsOfTheSameFourBytes) {
  std::vector<uint8_t> d24;  // GL: depth << 8 | stencil
  for (uint32_t v : {0x000000ABu, 0x80000000u, 0xFFFFFF00u}) append(d24, v);
  const std::vector<float> expected{0.0f, 8388608.0f / 16777215.0f, 1.0f};
  EXPECT_EQ(decodeDepth(image("D24", 3, 1, d24), "OpenGL"), expected);
  EXPECT_EQ(decodeDepth(image("D24S8", 3, 1, d24), "OpenGL"), expected);
  // The same bytes read as Vulkan's layout (the mistake the self-check exists to catch) differ.
  EXPECT_NE(decodeDepth(image("D24S8", 3, 1, d24), "OpenGL", DepthDecodeFault::Unorm24LowBits), expected);
  // Vulkan's D24S8 is never 4 bytes a pixel: that size is GL's layout and is refused there.
  EXPECT_THROW(decodeDepth(image("D24S8", 3, 1, d24), "Vulkan"), ImportProblem);
}

TEST(DepthDecoding, StencilPlaneAndInterleavedStencilAreSkipped) {
  std::vector<uint8_t> d24s8;  // 4-byte depth texels, then a 1-byte stencil plane
  for (uint32_t v : {0x00000001u, 0x00FFFFFFu}) append(d24s8, v);
  d24s8.insert(d24s8.end(), {0x7F, 0x80});
  EXPECT_EQ(decodeDepth(image("D24S8", 2, 1, d24s8), "Vulkan"), (std::vector<float>{1.0f / 16777215.0f, 1.0f}));
  std::vector<uint8_t> d32s8;  // float depth, stencil and padding per texel
  for (float f : {0.25f, 0.75f}) {
    append(d32s8, f);
    append(d32s8, uint32_t(0xFF));
  }
  EXPECT_EQ(decodeDepth(image("D32S8", 2, 1, d32s8), "Vulkan"), (std::vector<float>{0.25f, 0.75f}));
  EXPECT_EQ(decodeDepth(image("D32S8", 2, 1, d32s8), "OpenGL"), (std::vector<float>{0.25f, 0.75f}));
}

TEST(DepthDecoding, UnknownFormatsAndWrongSizesAreNamed) {
  try {
    decodeDepth(image("R32_FLOAT", 1, 1, {0, 0, 0, 0}), "Vulkan");
    FAIL();
  } catch (const ImportProblem& e) {
    EXPECT_EQ(e.field, "--depth");
    EXPECT_NE(std::string(e.what()).find("Vulkan depth format R32_FLOAT is not supported (supported for Vulkan: D16"),
              std::string::npos) << e.what();
  }
  EXPECT_THROW(decodeDepth(image("D32", 2, 1, {0, 0, 0, 0}), "Vulkan"), ImportProblem);
  try {  // an API with no measured layouts is refused, not decoded as another API's
    decodeDepth(image("D32", 1, 1, {0, 0, 0, 0}), "D3D11");
    FAIL();
  } catch (const ImportProblem& e) {
    EXPECT_NE(std::string(e.what()).find("(supported for D3D11: none)"), std::string::npos) << e.what();
  }
}

TEST(NormalDecoding, FloatTargetsAreTakenAsTheyAre) {
  std::vector<uint8_t> rgba16f;
  for (uint16_t h : {uint16_t(0x3C00), uint16_t(0xB800), uint16_t(0x0000), uint16_t(0x3C00)}) append(rgba16f, h);
  EXPECT_EQ(decodeNormals(image("R16G16B16A16_FLOAT", 1, 1, rgba16f)), (std::vector<float>{1.0f, -0.5f, 0.0f}));
}

TEST(NormalDecoding, FixedPointIsUnpackedAndNormalised) {
  // BGRA order: x is the third byte. 255 -> 1, 0 -> -1, 128 -> 0.0039; normalised.
  const auto n = decodeNormals(image("B8G8R8A8_UNORM", 1, 1, {0, 0, 255, 255}, true));
  const float len = std::sqrt(1.0f + 1.0f + 1.0f);
  EXPECT_FLOAT_EQ(n[0], 1.0f / len);
  EXPECT_FLOAT_EQ(n[1], -1.0f / len);
  EXPECT_FLOAT_EQ(n[2], -1.0f / len);
  const auto s = decodeNormals(image("R8G8B8A8_SNORM", 1, 1, {0, 127, 0, 0}));
  EXPECT_EQ(s, (std::vector<float>{0.0f, 1.0f, 0.0f}));
}

TEST(NormalDecoding, TwoComponentAndSrgbTargetsAreRefused) {
  EXPECT_THROW(decodeNormals(image("R16G16_FLOAT", 1, 1, {0, 0, 0, 0})), ImportProblem);
  EXPECT_THROW(decodeNormals(image("R8G8B8A8_SRGB", 1, 1, {0, 0, 0, 0})), ImportProblem);
}

}  // namespace
}  // namespace aor
