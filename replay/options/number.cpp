#include "options/number.h"

#include <charconv>
#include <cmath>

#include <fmt/format.h>

#include "core/input_error.h"

namespace aor {
namespace {

template <typename T>
T parseWhole(std::string_view text, const std::string& option, T min, T max, const char* kind) {
  T value{};
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  bool whole = !text.empty() && ec == std::errc() && end == text.data() + text.size();
  if (!whole || !std::isfinite(double(value)) || value < min || value > max)
    throw InputError("", std::nullopt, option, fmt::format("'{}' is not {} in {}..{}", text, kind, min, max));
  return value;
}

}  // namespace

int parseInt(std::string_view text, const std::string& option, int min, int max) {
  return parseWhole<int>(text, option, min, max, "a whole number");
}

long long parseLong(std::string_view text, const std::string& option, long long min, long long max) {
  return parseWhole<long long>(text, option, min, max, "a whole number");
}

double parseNumber(std::string_view text, const std::string& option, double min, double max) {
  return parseWhole<double>(text, option, min, max, "a number");
}

}  // namespace aor
