#include "cli/number_options.h"

#include <fmt/format.h>

#include "core/input_error.h"
#include "options/number.h"

namespace aor::cli {

namespace {

// `what`: "a finite number in [0, 1]", for the message and the help.
template <typename Parse>
CLI::Validator validator(const std::string& what, Parse parse) {
  return CLI::Validator(
      [parse, what](std::string& text) -> std::string {
        try {
          parse(text);
          return {};
        } catch (const InputError&) {
          return fmt::format("'{}' is not {}", text, what);
        }
      },
      what);
}

}  // namespace

CLI::Validator numberIn(double min, double max) {
  return validator(fmt::format("a finite number in [{:g}, {:g}]", min, max),
                   [min, max](const std::string& text) { parseNumber(text, "", min, max); });
}

CLI::Validator wholeIn(long long min, long long max) {
  return validator(fmt::format("a whole number in [{}, {}]", min, max),
                   [min, max](const std::string& text) { parseLong(text, "", min, max); });
}

}  // namespace aor::cli
