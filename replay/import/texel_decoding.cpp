#include "import/texel_decoding.h"

#include <cmath>
#include <cstring>
#include <functional>

#include <fmt/format.h>

#include "import/import_problem.h"

namespace aor {

namespace {

template <typename T>
T load(const uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

float halfToFloat(uint16_t h) {
  const int exponent = (h >> 10) & 0x1F, mantissa = h & 0x3FF;
  const float sign = (h & 0x8000) ? -1.0f : 1.0f;
  if (exponent == 0) return sign * std::ldexp(float(mantissa), -24);
  if (exponent == 31) return mantissa ? NAN : sign * INFINITY;
  return sign * std::ldexp(float(mantissa | 0x400), exponent - 25);
}

size_t pixelCount(const TexelImage& image) { return size_t(image.width) * size_t(image.height); }

// How one depth format is laid out in GetTextureData's bytes: depth of pixel i at i * stride.
// Stencil, when the format has it, either follows all depth texels (a plane) or sits beside each.
struct DepthLayout {
  const char* name;
  std::vector<size_t> bytesPerPixel;  // the sizes RenderDoc returns for it
  size_t stride(size_t bytesPerPixelSeen) const {
    return bytesPerPixelSeen == 5 ? 4 : bytesPerPixelSeen;  // 4-byte depth + a 1-byte stencil plane
  }
  std::function<float(const uint8_t*)> texel;
};

const std::vector<DepthLayout>& depthLayouts() {
  static const std::vector<DepthLayout> layouts = {
      {"D16", {2}, [](const uint8_t* p) { return float(load<uint16_t>(p)) / 65535.0f; }},
      {"D24", {4}, [](const uint8_t* p) { return float(load<uint32_t>(p) & 0xFFFFFFu) / 16777215.0f; }},
      {"D24S8", {4, 5}, [](const uint8_t* p) { return float(load<uint32_t>(p) & 0xFFFFFFu) / 16777215.0f; }},
      {"D32", {4}, [](const uint8_t* p) { return load<float>(p); }},
      {"D32S8", {8, 5}, [](const uint8_t* p) { return load<float>(p); }},
  };
  return layouts;
}

struct NormalEncoding {
  int bytesPerComponent;
  bool isFloat;
  bool isSigned;
};

// Per-component formats RenderDoc names R8G8B8A8_UNORM, R16G16B16A16_FLOAT, B8G8R8A8_UNORM, ...
bool parseComponentFormat(const std::string& name, int& components, NormalEncoding& encoding) {
  const size_t underscore = name.rfind('_');
  if (underscore == std::string::npos) return false;
  const std::string channels = name.substr(0, underscore), kind = name.substr(underscore + 1);
  int bits = 0;
  components = 0;
  for (size_t i = 0; i < channels.size();) {
    if (!std::strchr("RGBA", channels[i])) return false;
    size_t j = i + 1;
    int b = 0;
    while (j < channels.size() && std::isdigit(static_cast<unsigned char>(channels[j]))) b = b * 10 + (channels[j++] - '0');
    if (b == 0 || (bits && b != bits)) return false;
    bits = b;
    ++components;
    i = j;
  }
  if (bits % 8) return false;
  encoding.bytesPerComponent = bits / 8;
  encoding.isFloat = kind == "FLOAT";
  encoding.isSigned = kind == "SNORM";
  if (!encoding.isFloat && kind != "UNORM" && kind != "SNORM") return false;
  if (encoding.isFloat && bits != 16 && bits != 32) return false;
  return bits <= 16 || encoding.isFloat;
}

float fixedPointComponent(const uint8_t* p, const NormalEncoding& e) {
  if (e.bytesPerComponent == 1)
    return e.isSigned ? std::max(float(load<int8_t>(p)) / 127.0f, -1.0f) : float(*p) / 255.0f * 2.0f - 1.0f;
  return e.isSigned ? std::max(float(load<int16_t>(p)) / 32767.0f, -1.0f)
                    : float(load<uint16_t>(p)) / 65535.0f * 2.0f - 1.0f;
}

void normalise(float* n) {
  const float length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (length > 0.0f)
    for (int i = 0; i < 3; ++i) n[i] /= length;
}

void checkSize(const TexelImage& image, size_t bytesPerPixel) {
  if (image.bytes.size() != pixelCount(image) * bytesPerPixel)
    throw ImportProblem("--normals", fmt::format("RenderDoc returned {} bytes for the {}x{} {} target, expected {}",
                                                 image.bytes.size(), image.width, image.height, image.format,
                                                 pixelCount(image) * bytesPerPixel));
}

}  // namespace

const char* supportedDepthFormats() { return "D16, D24 (X8_D24), D24S8, D32, D32S8"; }

std::vector<float> decodeDepth(const TexelImage& image) {
  const size_t pixels = pixelCount(image);
  for (const DepthLayout& layout : depthLayouts()) {
    if (image.format != layout.name) continue;
    for (size_t bpp : layout.bytesPerPixel) {
      if (image.bytes.size() != pixels * bpp) continue;
      std::vector<float> depth(pixels);
      const size_t stride = layout.stride(bpp);
      for (size_t i = 0; i < pixels; ++i) depth[i] = layout.texel(image.bytes.data() + i * stride);
      return depth;
    }
    throw ImportProblem("--depth", fmt::format("RenderDoc returned {} bytes for the {}x{} {} depth target, which "
                                               "does not match its layout",
                                               image.bytes.size(), image.width, image.height, image.format));
  }
  throw ImportProblem("--depth", fmt::format("depth format {} is not supported (supported: {})", image.format,
                                             supportedDepthFormats()));
}

const char* supportedNormalFormats() {
  return "3 or 4 components of FLOAT (16, 32 bits), UNORM or SNORM (8, 16 bits), RGB or BGR order, and "
         "R10G10B10A2_UNORM";
}

std::vector<float> decodeNormals(const TexelImage& image) {
  const size_t pixels = pixelCount(image);
  std::vector<float> normals(pixels * 3);
  if (image.format == "R10G10B10A2_UNORM") {
    checkSize(image, 4);
    for (size_t i = 0; i < pixels; ++i) {
      const uint32_t v = load<uint32_t>(image.bytes.data() + 4 * i);
      for (int c = 0; c < 3; ++c) normals[3 * i + c] = float((v >> (10 * c)) & 0x3FF) / 1023.0f * 2.0f - 1.0f;
      normalise(&normals[3 * i]);
    }
    return normals;
  }
  int components = 0;
  NormalEncoding e{};
  if (!parseComponentFormat(image.format, components, e) || components < 3)
    throw ImportProblem("--normals", fmt::format("normal target format {} is not supported (supported: {})",
                                                 image.format, supportedNormalFormats()));
  const size_t bytesPerPixel = size_t(components) * size_t(e.bytesPerComponent);
  checkSize(image, bytesPerPixel);
  for (size_t i = 0; i < pixels; ++i) {
    const uint8_t* texel = image.bytes.data() + i * bytesPerPixel;
    float* n = &normals[3 * i];
    for (int c = 0; c < 3; ++c) {
      const int stored = image.bgra ? 2 - c : c;  // B, G, R: x is the third component
      const uint8_t* p = texel + size_t(stored) * size_t(e.bytesPerComponent);
      if (!e.isFloat) n[c] = fixedPointComponent(p, e);
      else n[c] = e.bytesPerComponent == 2 ? halfToFloat(load<uint16_t>(p)) : load<float>(p);
    }
    if (!e.isFloat) normalise(n);
  }
  return normals;
}

}  // namespace aor
