#include "replay_loop/readback.h"

#include <cstring>
#include <stdexcept>

#include <fmt/format.h>
#include <glm/gtc/packing.hpp>

namespace aor {
namespace {

// Every half-float bit pattern converted once (by the same glm function, so results are identical):
// the read-back converts up to 4 halves per pixel, and a table lookup is several times cheaper.
const std::vector<float>& halfToFloat() {
  static const std::vector<float> table = [] {
    std::vector<float> t(65536);
    for (uint32_t h = 0; h < 65536; ++h) t[h] = glm::unpackHalf1x16(uint16_t(h));
    return t;
  }();
  return table;
}

enum class Encoding { Half, Float, Unorm8, Snorm8, Uint32, Uint16, Unorm16, Uint8 };
struct FormatEncoding {
  VkFormat format;
  Encoding encoding;
  uint32_t channels;
};
constexpr FormatEncoding kEncodings[] = {
    {VK_FORMAT_R16_SFLOAT, Encoding::Half, 1},          {VK_FORMAT_R16G16_SFLOAT, Encoding::Half, 2},
    {VK_FORMAT_R16G16B16A16_SFLOAT, Encoding::Half, 4}, {VK_FORMAT_R32_SFLOAT, Encoding::Float, 1},
    {VK_FORMAT_R32G32_SFLOAT, Encoding::Float, 2},      {VK_FORMAT_R32G32B32A32_SFLOAT, Encoding::Float, 4},
    {VK_FORMAT_R8_UNORM, Encoding::Unorm8, 1},          {VK_FORMAT_R8G8_UNORM, Encoding::Unorm8, 2},
    {VK_FORMAT_R8G8B8A8_UNORM, Encoding::Unorm8, 4},    {VK_FORMAT_R8G8B8A8_SNORM, Encoding::Snorm8, 4},
    {VK_FORMAT_R8G8_SNORM, Encoding::Snorm8, 2},        {VK_FORMAT_R32_UINT, Encoding::Uint32, 1},
    {VK_FORMAT_R16_UINT, Encoding::Uint16, 1},          {VK_FORMAT_R16_UNORM, Encoding::Unorm16, 1},
    {VK_FORMAT_R8_UINT, Encoding::Uint8, 1},
};

const FormatEncoding* encodingOf(VkFormat format) {
  for (const auto& e : kEncodings)
    if (e.format == format) return &e;
  return nullptr;
}

}  // namespace

uint32_t decodableChannels(VkFormat format) {
  const auto* e = encodingOf(format);
  return e ? e->channels : 0;
}

std::vector<float> decodeTexels(const void* data, VkFormat format, size_t texels) {
  const auto* e = encodingOf(format);
  if (!e) throw std::logic_error(fmt::format("read-back cannot decode VkFormat {}", int(format)));
  size_t n = texels * e->channels;
  std::vector<float> out(n);
  switch (e->encoding) {
    case Encoding::Half: {
      const auto* h = static_cast<const uint16_t*>(data);
      const float* table = halfToFloat().data();
      for (size_t i = 0; i < n; ++i) out[i] = table[h[i]];
      break;
    }
    case Encoding::Float: std::memcpy(out.data(), data, n * sizeof(float)); break;
    case Encoding::Unorm8:
      for (size_t i = 0; i < n; ++i) out[i] = float(static_cast<const uint8_t*>(data)[i]) / 255.0f;
      break;
    case Encoding::Snorm8:
      for (size_t i = 0; i < n; ++i) out[i] = std::max(-1.0f, float(static_cast<const int8_t*>(data)[i]) / 127.0f);
      break;
    case Encoding::Uint32:
      for (size_t i = 0; i < n; ++i) out[i] = float(static_cast<const uint32_t*>(data)[i]);
      break;
    case Encoding::Uint16:
      for (size_t i = 0; i < n; ++i) out[i] = float(static_cast<const uint16_t*>(data)[i]);
      break;
    case Encoding::Unorm16:
      for (size_t i = 0; i < n; ++i) out[i] = float(static_cast<const uint16_t*>(data)[i]) / 65535.0f;
      break;
    case Encoding::Uint8:
      for (size_t i = 0; i < n; ++i) out[i] = float(static_cast<const uint8_t*>(data)[i]);
      break;
  }
  return out;
}

DecodedOutput decodeOutput(const void* data, VkFormat format, const OutputLayout& layout, size_t pixels) {
  uint32_t channels = decodableChannels(format);
  if (channels == 0 || uint32_t(layout.visibilityChannel) >= channels ||
      (layout.bentChannel >= 0 && uint32_t(layout.bentChannel) + 3 > channels))
    throw std::logic_error(fmt::format("output of VkFormat {} cannot hold the declared channels", int(format)));
  DecodedOutput out;
  out.visibility.resize(pixels);
  if (layout.bentChannel >= 0) out.bent.resize(pixels * 3);
  if (format == VK_FORMAT_R16_SFLOAT || format == VK_FORMAT_R16G16B16A16_SFLOAT) {
    // The common case without a temporary: straight from the mapped halves.
    const auto* halves = static_cast<const uint16_t*>(data);
    const float* toFloat = halfToFloat().data();
    for (size_t i = 0; i < pixels; ++i) {
      out.visibility[i] = toFloat[halves[channels * i + size_t(layout.visibilityChannel)]];
      if (layout.bentChannel < 0) continue;
      for (size_t c = 0; c < 3; ++c) out.bent[3 * i + c] = toFloat[halves[channels * i + size_t(layout.bentChannel) + c]];
    }
    return out;
  }
  std::vector<float> all = decodeTexels(data, format, pixels);
  for (size_t i = 0; i < pixels; ++i) {
    out.visibility[i] = all[channels * i + size_t(layout.visibilityChannel)];
    if (layout.bentChannel < 0) continue;
    for (size_t c = 0; c < 3; ++c) out.bent[3 * i + c] = all[channels * i + size_t(layout.bentChannel) + c];
  }
  return out;
}

}  // namespace aor
