#pragma once
// The one error type for bad input (files, captures, settings). The CLI maps it to exit code 2
// and prints what(), which always names the file, the frame (when there is one) and the field.
#include <optional>
#include <stdexcept>
#include <string>

namespace aor {

struct InputError : std::runtime_error {
  InputError(std::string file, std::optional<int> frame, std::string field, const std::string& problem);
  std::string file;          // path as the user would recognise it; empty when not about a file
  std::optional<int> frame;  // index into capture.json "frames"
  std::string field;         // JSON field, EXR channel or setting key
};

}  // namespace aor
