#pragma once
// EXR and PNG files of float planes. EXR writing is deterministic (no timestamps in headers) and
// uses lossless ZIP compression so shipped captures stay small.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace aor {

enum class ExrPixelType { Half, Float };

struct ExrChannel {
  std::string name;
  ExrPixelType type = ExrPixelType::Float;
  const float* data = nullptr;  // width*height floats, row 0 at the top
};

void writeExr(const std::filesystem::path& path, int width, int height, const std::vector<ExrChannel>& channels);

struct ExrHeaderInfo {
  int width = 0, height = 0;
  std::map<std::string, ExrPixelType> channels;
};
// Throws InputError naming the file when it is missing, truncated or not an EXR.
ExrHeaderInfo readExrHeader(const std::filesystem::path& path);
// Reads the named channels as float planes; throws InputError naming file and channel.
std::map<std::string, std::vector<float>> readExrChannels(const std::filesystem::path& path,
                                                          const std::vector<std::string>& names);

// 8-bit grayscale preview of values in [0,1] (clamped; NaN shown as 0).
void writePngGray(const std::filesystem::path& path, int width, int height, const float* values);
// 8-bit RGB; values width*height*3 in [0,1].
void writePngRgb(const std::filesystem::path& path, int width, int height, const float* values);
// The PNG file writePngGray (channels 1) or writePngRgb (3) would write, as bytes in memory.
std::string encodePng(int width, int height, int channels, const float* values);

}  // namespace aor
