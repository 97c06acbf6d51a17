#pragma once
// What the RenderDoc test programs (rd_scene, rd_gl_scene) share: their read-back files and the
// capture file's name. Failures throw std::runtime_error; each program's main reports them.
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <renderdoc_app.h>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

namespace aor::rdtest {

template <typename T>
void writeBinary(const std::filesystem::path& path, const std::vector<T>& values) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size() * sizeof(T)));
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

inline nlohmann::json matrixJson(const glm::mat4& m) {
  auto a = nlohmann::json::array();
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) a.push_back(double(m[c][r]));
  return a;
}

// RenderDoc names its files after a template; the tests want NNNN.rdc.
inline void moveNewestCapture(RENDERDOC_API_1_6_0* api, const std::filesystem::path& target) {
  const uint32_t count = api->GetNumCaptures();
  if (count == 0) throw std::runtime_error("RenderDoc made no capture");
  uint32_t length = 0;
  api->GetCapture(count - 1, nullptr, &length, nullptr);
  std::string path(length, '\0');
  api->GetCapture(count - 1, path.data(), &length, nullptr);
  path.resize(std::strlen(path.c_str()));
  std::filesystem::rename(path, target);
}

}  // namespace aor::rdtest
