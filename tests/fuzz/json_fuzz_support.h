#pragma once
// Shared by the JSON-file fuzz targets: the input goes to a private file (the loaders read files,
// so the size, FIFO and regular-file checks are on the path too), and the bounded parser's two
// paths are held to the same answer.
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "core/input_error.h"
#include "core/json_input.h"

namespace aor::fuzz {

// One private folder per process, removed when it exits (the regression replays run in every test
// suite), holding one file per name, rewritten for every input (libFuzzer runs one at a time).
struct PrivateFolder {
  std::filesystem::path path;
  PrivateFolder() : path(std::filesystem::temp_directory_path() / ("aor-fuzz-" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(path);
  }
  ~PrivateFolder() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
};

inline const PrivateFolder& privateFolder() {
  static const PrivateFolder folder;
  return folder;
}

inline std::filesystem::path inputFile(const std::string& name, const uint8_t* data, size_t size) {
  const std::filesystem::path& dir = privateFolder().path;
  const auto path = dir / name;
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), std::streamsize(size));
  return path;
}

// parseBoundedJson (simdjson, then nlohmann for errors) and the nlohmann path alone must agree:
// the same document, or both an InputError. Anything else is a finding (__builtin_trap).
inline void checkBothParsersAgree(const uint8_t* data, size_t size, const JsonLimits& limits) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  std::optional<nlohmann::json> fast, slow;
  try {
    fast = parseBoundedJson(text, limits, "input");
  } catch (const InputError&) {
  }
  try {
    slow = detail::parseBoundedJsonSlowly(text, limits, "input");
  } catch (const InputError&) {
  }
  if (fast.has_value() != slow.has_value()) __builtin_trap();
  if (fast && *fast != *slow) __builtin_trap();
}

}  // namespace aor::fuzz
