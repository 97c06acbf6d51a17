#include "options/size.h"

#include <cctype>
#include <charconv>
#include <optional>

#include <fmt/format.h>

#include "core/input_error.h"

namespace aor {
namespace {

// One positive number the way sscanf's %d reads it, leaving `text` after its last digit. Negative
// numbers and zero are refused; so is a value past INT_MAX (undefined for sscanf).
std::optional<int> takePositive(std::string_view& text) {
  size_t i = 0;
  while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
  if (i < text.size() && text[i] == '+') ++i;
  if (i == text.size() || !std::isdigit(static_cast<unsigned char>(text[i]))) return std::nullopt;
  int value = 0;
  auto [end, ec] = std::from_chars(text.data() + i, text.data() + text.size(), value);
  if (ec != std::errc() || value <= 0) return std::nullopt;
  text.remove_prefix(size_t(end - text.data()));
  return value;
}

}  // namespace

std::pair<int, int> parseSize(std::string_view text, const std::string& option) {
  std::string_view rest = text;
  auto w = takePositive(rest);
  bool separator = w && !rest.empty() && rest.front() == 'x';
  if (separator) rest.remove_prefix(1);
  auto h = separator ? takePositive(rest) : std::nullopt;
  if (!h || !rest.empty())
    throw InputError("", std::nullopt, option, fmt::format("'{}' is not WxH with positive sizes", text));
  return {*w, *h};
}

}  // namespace aor
