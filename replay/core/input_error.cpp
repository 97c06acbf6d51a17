#include "core/input_error.h"

#include <algorithm>
#include <cctype>
#include <utility>

#include "core/plain_text.h"

namespace aor {
namespace {

bool endsWithExr(const std::string& file) {
  if (file.size() < 4) return false;
  std::string ext = file.substr(file.size() - 4);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".exr";
}

// At most `limit` bytes of `text` (cut at a character boundary), then "... (N bytes)": a field
// name or problem taken from a file is never echoed whole (a key can be 200 MB long).
std::string shortened(const std::string& text, size_t limit) {
  if (text.size() <= limit) return text;
  size_t cut = limit;
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;
  return text.substr(0, cut) + "... (" + std::to_string(text.size()) + " bytes)";
}

constexpr size_t kMaxFieldBytes = 100;
constexpr size_t kMaxProblemBytes = 1000;

// "<file>: frame <N>: <label> "<field>": <problem>", each part only when known. The label is
// "channel" for EXR files, "field" for other files (JSON) and "setting" when there is no file.
std::string composeMessage(const std::string& file, const std::optional<int>& frame, const std::string& field,
                           const std::string& problem) {
  std::string msg;
  if (!file.empty()) msg += file + ": ";
  if (frame) msg += "frame " + std::to_string(*frame) + ": ";
  if (!field.empty()) {
    const char* label = file.empty() ? "setting" : endsWithExr(file) ? "channel" : "field";
    msg += std::string(label) + " \"" + shortened(field, kMaxFieldBytes) + "\": ";
  }
  msg += problem.empty() ? std::string("invalid") : shortened(problem, kMaxProblemBytes);
  // One line that moves no cursor: newlines from library messages, tabs, escapes, C1 controls.
  return controlCharactersBlanked(std::move(msg));
}

}  // namespace

InputError::InputError(std::string file, std::optional<int> frame, std::string field, const std::string& problem)
    : std::runtime_error(composeMessage(file, frame, field, problem)),
      file(std::move(file)),
      frame(frame),
      field(std::move(field)) {}

}  // namespace aor
