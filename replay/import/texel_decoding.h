#pragma once
// Decodes the texels RenderDoc's GetTextureData returns for a depth attachment or a normal target
// into the floats of a capture's G-buffer. Formats are named as RenderDoc names them.
#include <cstdint>
#include <string>
#include <vector>

namespace aor {

struct TexelImage {
  int width = 0, height = 0;
  std::string format;       // RenderDoc's name: D16, D24, D24S8, D32, D32S8, R16G16B16A16_FLOAT, ...
  bool bgra = false;        // components stored B, G, R(, A)
  std::vector<uint8_t> bytes;
  int samples = 1;          // of a multisampled texture, one sample's texels (RenderDoc lays those out its own way)
};

// A mistake made on purpose, for the tests that show the self-check catches it.
enum class DepthDecodeFault { None, Unorm24LowBits };

// Depth values as the API defines them (unorm texels c / (2^bits - 1), float texels as they are),
// from the bytes RenderDoc returns for that API ("Vulkan", "OpenGL") and format: the layout is
// chosen by both, never by the byte count alone. Throws ImportProblem (field --depth) for a
// format not measured for the API or a size that does not fit its layout.
std::vector<float> decodeDepth(const TexelImage& image, const std::string& api,
                               DepthDecodeFault fault = DepthDecodeFault::None);
std::string supportedDepthFormats(const std::string& api, bool multisampled = false);
// One step of a unorm depth format (1 / (2^bits - 1)); 0 for float depth.
double depthFormatStep(const std::string& format);

// Normals, xyz interleaved per pixel. Float targets are taken as they hold them; fixed-point ones
// are unpacked (unorm: 2c - 1, snorm: c) and normalised (a zero vector stays zero).
// Throws ImportProblem (field --normals) for formats with fewer than three components or unknown.
std::vector<float> decodeNormals(const TexelImage& image);
const char* supportedNormalFormats();

}  // namespace aor
