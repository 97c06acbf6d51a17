#include "import/texel_decoding.h"

#include <cmath>
#include <cstring>

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

// How RenderDoc's GetTextureData lays out one depth format of one API: depth of pixel i at
// i * stride. Stencil, when the format has it, either follows all depth texels (a plane) or sits
// beside each. Only layouts measured with the test programs are listed (replay/import/README.md).
struct DepthLayout {
  const char* api;
  const char* name;
  bool multisampled;     // one sample of a multisampled target, which RenderDoc copies out through its own pass
  size_t bytesPerPixel;  // the size RenderDoc returns for it
  size_t stride;         // bytes from one depth texel to the next
  float (*texel)(const uint8_t*);
};

float unorm16(const uint8_t* p) { return float(load<uint16_t>(p)) / 65535.0f; }
float unorm24Low(const uint8_t* p) { return float(load<uint32_t>(p) & 0xFFFFFFu) / 16777215.0f; }
float unorm24High(const uint8_t* p) { return float(load<uint32_t>(p) >> 8) / 16777215.0f; }
float float32(const uint8_t* p) { return load<float>(p); }

const std::vector<DepthLayout>& depthLayouts() {
  static const std::vector<DepthLayout> layouts = {
      {"Vulkan", "D16", false, 2, 2, unorm16},
      {"Vulkan", "D24", false, 4, 4, unorm24Low},
      {"Vulkan", "D24S8", false, 5, 4, unorm24Low},  // a plane of 1-byte stencil follows
      {"Vulkan", "D32", false, 4, 4, float32},
      {"Vulkan", "D32S8", false, 8, 8, float32},     // float, stencil, padding per texel
      {"Vulkan", "D32S8", false, 5, 4, float32},     // a stencil plane
      // One sample of a multisampled target (rd_scene --samples 4 against its sample-0 resolve):
      // D24S8 loses its stencil plane; D32 and D32S8 come back bit for bit, D16 and D24S8 up to one
      // step off at some texels (41 and 8959 of 14400), RenderDoc's copy going through floats.
      {"Vulkan", "D16", true, 2, 2, unorm16},
      {"Vulkan", "D24", true, 4, 4, unorm24Low},
      {"Vulkan", "D24S8", true, 4, 4, unorm24Low},
      {"Vulkan", "D32", true, 4, 4, float32},
      {"Vulkan", "D32S8", true, 8, 8, float32},
      {"OpenGL", "D16", false, 2, 2, unorm16},
      {"OpenGL", "D24", false, 4, 4, unorm24High},   // depth in the high 24 bits
      {"OpenGL", "D24S8", false, 4, 4, unorm24High}, // stencil in the low byte
      {"OpenGL", "D32", false, 4, 4, float32},
      {"OpenGL", "D32S8", false, 8, 8, float32},
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

double depthFormatStep(const std::string& format) {
  if (format == "D16") return 1.0 / 65535.0;
  if (format == "D24" || format == "D24S8") return 1.0 / 16777215.0;
  return 0.0;
}

std::string supportedDepthFormats(const std::string& api, bool multisampled) {
  std::string names;
  for (const DepthLayout& layout : depthLayouts())
    if (layout.api == api && layout.multisampled == multisampled &&
        names.find(layout.name + std::string(",")) == std::string::npos)
      names += std::string(layout.name) + ", ";
  return names.empty() ? "none" : names.substr(0, names.size() - 2);
}

std::vector<float> decodeDepth(const TexelImage& image, const std::string& api, DepthDecodeFault fault) {
  const size_t pixels = pixelCount(image);
  bool formatKnown = false;
  const bool multisampled = image.samples > 1;
  for (const DepthLayout& layout : depthLayouts()) {
    if (layout.api != api || image.format != layout.name || layout.multisampled != multisampled) continue;
    formatKnown = true;
    if (image.bytes.size() != pixels * layout.bytesPerPixel) continue;
    // The test-only fault reads GL's D24 as Vulkan's, the mistake the self-check must catch.
    const bool misread = fault == DepthDecodeFault::Unorm24LowBits && layout.texel == unorm24High;
    const auto texel = misread ? unorm24Low : layout.texel;
    std::vector<float> depth(pixels);
    for (size_t i = 0; i < pixels; ++i) depth[i] = texel(image.bytes.data() + i * layout.stride);
    return depth;
  }
  if (formatKnown)
    throw ImportProblem("--depth", fmt::format("RenderDoc returned {} bytes for the {}x{} {} {} depth target, which "
                                               "does not match a layout measured for it",
                                               image.bytes.size(), image.width, image.height, api, image.format));
  if (multisampled)
    throw ImportProblem("--depth", fmt::format("multisampled {} {} depth ({} samples) is not supported: RenderDoc's "
                                               "layout for it is not measured (multisampled {}: {})",
                                               api, image.format, image.samples, api, supportedDepthFormats(api, true)));
  throw ImportProblem("--depth", fmt::format("{} depth format {} is not supported (supported for {}: {})", api,
                                             image.format, api, supportedDepthFormats(api)));
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
