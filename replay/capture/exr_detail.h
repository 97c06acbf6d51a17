#pragma once
// Private to aor_capture: EXR access with the context (display name, frame index) that error
// messages need, and with the channel types image_io.h cannot express (UINT).
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace aor::detail {

// Size limits shared by capture.json validation and EXR reading.
inline constexpr int kMaxImageSide = 16384;
inline constexpr std::int64_t kMaxImagePixels = std::int64_t(16384) * 16384 / 4;  // 2^26

enum class ExrChannelKind { Half, Float, Uint };
const char* kindName(ExrChannelKind kind);

struct ExrHeaderDetail {
  int width = 0, height = 0;
  std::map<std::string, ExrChannelKind> channels;
};

// The header's channel names, sorted, comma-separated; "none" when there are none.
std::string channelList(const ExrHeaderDetail& h);

// Reads and checks the header of `path`: the file exists, is an OpenEXR image, its data window
// is sane, no channel is subsampled, and (for single-part scan-line files) every chunk of pixel
// data listed in the offset table lies inside the file, so truncated files are caught here.
// Errors are InputError(display, frame, ...).
ExrHeaderDetail readExrHeaderDetail(const std::filesystem::path& path, const std::string& display,
                                    std::optional<int> frame);

// Reads channels as float planes (row 0 at the top). When expectWidth/expectHeight are given the
// data window must have that size.
std::map<std::string, std::vector<float>> readExrChannelsDetail(const std::filesystem::path& path,
                                                                const std::string& display,
                                                                std::optional<int> frame,
                                                                const std::vector<std::string>& names,
                                                                std::optional<int> expectWidth = std::nullopt,
                                                                std::optional<int> expectHeight = std::nullopt);

// How a path is shown in messages when no user-given spelling is at hand: relative to the current
// directory when it lies below it, else absolute.
std::string displayPath(const std::filesystem::path& path);

}  // namespace aor::detail
