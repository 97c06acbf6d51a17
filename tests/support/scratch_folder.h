#pragma once
// A test program's own scratch folder, removed when the program ends (ctest runs one test a
// process, so nothing is left in the temporary folder), and reading a JSON file it holds.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace aor::test {

// TEMP/PREFIX_PID; the first call's prefix names it for the whole program.
inline const std::filesystem::path& processScratchFolder(const std::string& prefix) {
  static const struct Root {
    std::filesystem::path path;
    ~Root() {
      std::error_code ignored;
      std::filesystem::remove_all(path, ignored);
    }
  } root{std::filesystem::path(testing::TempDir()) / (prefix + "_" + std::to_string(::getpid()))};
  return root.path;
}

inline nlohmann::json readJsonFile(const std::filesystem::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

}  // namespace aor::test
