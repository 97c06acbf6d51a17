#pragma once
// Reading a JSON file a user points aoreplay at (capture.json, --expect, compare's inputs, result
// markers) within bounds, so that no such file can crash, hang or exhaust the tool:
//   - only regular files are read: a FIFO would block for ever, a device never end;
//   - at most JsonLimits::maxBytes, checked before reading;
//   - nesting deeper than maxDepth is refused before anything deeper is built (nlohmann's DOM
//     functions recurse, so a 60 000-deep document would overflow the stack later);
//   - an array of more than maxArrayElements is refused before its elements are converted;
//   - a key that appears twice in one object is an error (nlohmann would keep the last silently).
// Parsing is linear in the size: simdjson parses, and only when it reports an error is the text
// parsed again with nlohmann's (slower) SAX parser, for a message with the line and column.
// Errors are InputError naming the file and, where there is one, the field as a path
// ("frames[3].view", "scene.a.b").
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace aor {

struct JsonLimits {
  std::uint64_t maxBytes = std::uint64_t(16) << 20;
  std::uint64_t maxArrayElements = 1'000'000;
  int maxDepth = 128;  // objects and arrays inside each other; the top-level value is depth 1
};

// `display` is how messages name the file (default: path as given).
nlohmann::json readBoundedJson(const std::filesystem::path& path, const JsonLimits& limits,
                               const std::string& display = {});
// A regular file's bytes, at most `maxBytes` (the checks readBoundedJson makes before parsing), for
// other text a user points aoreplay at (a technique's shaders). Throws InputError naming `display`.
std::string readBoundedText(const std::filesystem::path& path, std::uint64_t maxBytes, const std::string& display);
// The same for text already in memory.
nlohmann::json parseBoundedJson(std::string_view text, const JsonLimits& limits, const std::string& display);

// `text` for an error message: JSON-quoted and escaped, at most `maxChars` bytes of it (cut at a
// character boundary), then "... (N bytes)".
std::string quoteForMessage(std::string_view text, size_t maxChars = 100);

namespace detail {
// The slow path alone (nlohmann's parser), which must give the same document or error as
// parseBoundedJson: the fuzz targets compare the two.
nlohmann::json parseBoundedJsonSlowly(std::string_view text, const JsonLimits& limits, const std::string& display);
}  // namespace detail

}  // namespace aor
