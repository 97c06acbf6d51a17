#include "core/plain_text.h"

#include <algorithm>

#include <fmt/format.h>

#include "core/input_error.h"
#include "core/json_input.h"

namespace aor {
namespace {

// The length of the valid UTF-8 sequence at `at` (1 for ASCII), or 0 when it is not one.
size_t sequenceLength(std::string_view text, size_t at) {
  const auto byte = [&](size_t i) { return static_cast<unsigned char>(text[i]); };
  const unsigned char lead = byte(at);
  const size_t n = lead < 0x80 ? 1 : (lead >> 5) == 0x6 ? 2 : (lead >> 4) == 0xe ? 3 : (lead >> 3) == 0x1e ? 4 : 0;
  if (n == 0 || at + n > text.size()) return 0;
  for (size_t i = 1; i < n; ++i)
    if ((byte(at + i) & 0xc0) != 0x80) return 0;
  return n;
}

// Control at `at`: C0, DEL, or C1 (U+0080..U+009F, encoded C2 80..C2 9F).
size_t controlLength(std::string_view text, size_t at, size_t length) {
  const auto lead = static_cast<unsigned char>(text[at]);
  if (length == 1 && (lead < 0x20 || lead == 0x7f)) return 1;
  if (length == 2 && lead == 0xc2 && static_cast<unsigned char>(text[at + 1]) < 0xa0) return 2;
  return 0;
}

}  // namespace

std::optional<std::string> controlCharacterIn(std::string_view text) {
  for (size_t at = 0; at < text.size();) {
    const size_t length = std::max<size_t>(1, sequenceLength(text, at));
    if (controlLength(text, at, length))
      return fmt::format("\\x{:02x} at byte {}", static_cast<unsigned char>(text[at + length - 1]), at);
    at += length;
  }
  return std::nullopt;
}

std::string withoutControlCharacters(std::string text, const std::string& file, const std::string& field) {
  if (auto at = controlCharacterIn(text)) throw InputError(file, std::nullopt, field, fmt::format("{} holds a control character ({})", quoteForMessage(text), *at));
  return text;
}

std::string controlCharactersBlanked(std::string text) {
  for (size_t at = 0; at < text.size();) {
    const size_t length = std::max<size_t>(1, sequenceLength(text, at));
    if (controlLength(text, at, length)) text.replace(at, length, length, ' ');
    at += length;
  }
  return text;
}

std::string printable(std::string_view text, bool keepLines) {
  std::string out;
  out.reserve(text.size());
  for (size_t at = 0; at < text.size();) {
    const size_t length = sequenceLength(text, at);
    const bool kept = keepLines && (text[at] == '\n' || text[at] == '\t');
    if (length == 0 || (controlLength(text, at, length) && !kept)) {
      for (size_t i = 0; i < std::max<size_t>(1, length); ++i) out += fmt::format("\\x{:02x}", static_cast<unsigned char>(text[at + i]));
      at += std::max<size_t>(1, length);
      continue;
    }
    out.append(text.substr(at, length));
    at += length;
  }
  return out;
}

}  // namespace aor
