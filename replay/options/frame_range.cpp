#include "options/frame_range.h"

#include <charconv>
#include <string_view>

#include <fmt/format.h>

#include "core/input_error.h"

namespace aor {

std::pair<int, int> frameRange(const Capture& capture, const std::string& frames) {
  int total = int(capture.frames.size());
  if (frames.empty()) return {0, total};
  auto colon = frames.find(':');
  auto parse = [&](std::string_view text, int fallback) {
    if (text.empty()) return fallback;
    int value = 0;
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size())
      throw InputError("", std::nullopt, "--frames", fmt::format("'{}' is not A:B with whole numbers", frames));
    return value;
  };
  if (colon == std::string::npos)
    throw InputError("", std::nullopt, "--frames", fmt::format("'{}' is not A:B (half-open, e.g. 3:4)", frames));
  std::string_view text(frames);
  int a = parse(text.substr(0, colon), 0), b = parse(text.substr(colon + 1), total);
  if (a < 0 || a >= b || b > total)
    throw InputError((capture.folder / "capture.json").string(), std::nullopt, "--frames",
                     fmt::format("{} is outside the capture's {} frames (need 0 <= A < B <= {})", frames, total, total));
  return {a, b};
}

}  // namespace aor
