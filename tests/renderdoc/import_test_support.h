#pragma once
// What the RenderDoc import tests share: running commands, scratch folders, reading the test
// programs' read-backs, and rendering rd_scene's frames.
#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

namespace aor::rdtest {
namespace fs = std::filesystem;

struct Command {
  int exitCode = -1;
  std::string output;
};

inline Command run(const std::string& command) {
  Command result;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer;
  while (size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe)) result.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

inline Command aoreplay(const std::string& arguments, const std::string& environment = "") {
  return run(fmt::format("{} {} {}", environment, AOR_EXE, arguments));
}

inline fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(AOR_BINARY_DIR) / "renderdoc-tests" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

template <typename T>
std::vector<T> readBinary(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), {});
  std::vector<T> values(bytes.size() / sizeof(T));
  std::memcpy(values.data(), bytes.data(), values.size() * sizeof(T));
  return values;
}

inline std::string readBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

inline nlohmann::json readJson(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

inline glm::mat4 matrixOf(const nlohmann::json& a) {
  glm::mat4 m;
  for (int i = 0; i < 16; ++i) m[i / 4][i % 4] = a.at(size_t(i)).get<float>();
  return m;
}

inline bool sameBits(const glm::mat4& a, const glm::mat4& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

inline float halfToFloat(uint16_t h) {
  const int e = (h >> 10) & 0x1F, m = h & 0x3FF;
  const float s = (h & 0x8000) ? -1.0f : 1.0f;
  if (e == 0) return s * std::ldexp(float(m), -24);
  return s * std::ldexp(float(m | 0x400), e - 25);
}

// rd_scene's frames: captures in DIR/captures, read-back in DIR/readback.
// `extra`: more rd_scene options (--camera LAYOUT, --stripped-names).
inline fs::path renderScene(const std::string& name, const std::string& format, bool reversed, int frames = 1,
                            const std::string& extra = "") {
  const fs::path dir = scratch(name);
  const Command c = run(fmt::format("{} --depth-format {} {} --frames {} --capture-dir {} --readback-dir {} {}",
                                    RD_SCENE_EXE, format, reversed ? "--reversed" : "", frames,
                                    (dir / "captures").string(), (dir / "readback").string(), extra));
  EXPECT_EQ(c.exitCode, 0) << c.output;
  return dir;
}

}  // namespace aor::rdtest
