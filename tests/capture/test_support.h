#pragma once
// Shared helpers for the capture tests: per-test temporary folders, synthetic frames, file
// manipulation and an InputError expectation that checks the message parts.
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "capture/capture.h"
#include "capture/image_io.h"
#include "core/input_error.h"

namespace aor::test {

namespace fs = std::filesystem;

// Each test gets its own empty folder (unique per process, removed afterwards).
class TempDirTest : public testing::Test {
 protected:
  void SetUp() override {
    const auto* info = testing::UnitTest::GetInstance()->current_test_info();
    dir = fs::path(testing::TempDir()) / ("aor_capture_tests-" + std::to_string(::getpid())) /
          (std::string(info->test_suite_name()) + "." + info->name());
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir, ec);
    fs::remove(dir.parent_path(), ec);  // only succeeds once empty
  }
  fs::path dir;
};

inline std::string readBytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline void writeBytes(const fs::path& p, const std::string& bytes) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  ASSERT_TRUE(out.good()) << p;
}

inline nlohmann::json readJson(const fs::path& p) { return nlohmann::json::parse(readBytes(p)); }
inline void writeJson(const fs::path& p, const nlohmann::json& j) { writeBytes(p, j.dump(2)); }

inline void truncateFile(const fs::path& p, std::uintmax_t size) { fs::resize_file(p, size); }

inline bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof(float)) == 0; }

// Deterministic pseudo-random values in [0, 1).
inline float hash01(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return static_cast<float>(x >> 8) / 16777216.0f;
}

inline GBuffer makeGBuffer(int w, int h, int seed, bool normals, bool depth2) {
  GBuffer g;
  g.width = w;
  g.height = h;
  const size_t n = static_cast<size_t>(w) * h;
  g.depth.resize(n);
  for (size_t i = 0; i < n; ++i) g.depth[i] = 0.2f + 0.7f * hash01(static_cast<std::uint32_t>(i * 31 + seed * 7919));
  g.depth[0] = 1.0f;  // a sky pixel
  if (normals) {
    g.normals.resize(3 * n);
    for (size_t i = 0; i < n; ++i) {
      const float a = 6.2831853f * hash01(static_cast<std::uint32_t>(i * 17 + seed * 104729 + 1));
      const float b = 1.5f * hash01(static_cast<std::uint32_t>(i * 13 + seed * 1299709 + 2));
      g.normals[3 * i + 0] = std::cos(a) * std::sin(b);
      g.normals[3 * i + 1] = std::cos(b);
      g.normals[3 * i + 2] = std::sin(a) * std::sin(b);
    }
  }
  if (depth2) {
    g.depth2.resize(n);
    for (size_t i = 0; i < n; ++i) g.depth2[i] = std::min(1.0f, g.depth[i] + 0.05f);
  }
  return g;
}

inline std::vector<float> makeReference(int w, int h, int seed) {
  std::vector<float> v(static_cast<size_t>(w) * h);
  for (size_t i = 0; i < v.size(); ++i) v[i] = hash01(static_cast<std::uint32_t>(i * 7 + seed * 31337 + 3));
  return v;
}

inline glm::mat4 makeView(int seed) {
  const glm::vec3 eye(1.0f + 0.37f * seed, 2.1f, 5.3f - 0.11f * seed);
  return glm::lookAt(eye, glm::vec3(0.1f, 0.3f * seed, -1.0f), glm::vec3(0, 1, 0));
}

// Standard depth, finite far (GLM_FORCE_DEPTH_ZERO_TO_ONE is set by aor_capture).
inline glm::mat4 makeProjection(int w, int h) {
  return glm::perspective(glm::radians(61.0f), static_cast<float>(w) / h, 0.1f, 57.3f);
}

// Reversed depth, infinite far, Vulkan y flip and a sub-pixel jitter.
inline glm::mat4 makeReversedInfiniteProjection(int w, int h) {
  const float f = 1.0f / std::tan(glm::radians(50.0f) / 2);
  glm::mat4 p(0.0f);
  p[0][0] = f * h / w;
  p[1][1] = -f;
  p[2][0] = 0.25f / w;
  p[2][1] = -0.25f / h;
  p[2][3] = -1.0f;
  p[3][2] = 0.05f;
  return p;
}

// Frames of a small valid capture: normals, references on every `refEvery`-th frame.
inline std::vector<CaptureFrameData> makeFrames(int w, int h, int count, bool normals = true, bool depth2 = false,
                                                int refEvery = 1) {
  std::vector<CaptureFrameData> frames;
  for (int i = 0; i < count; ++i) {
    CaptureFrameData f;
    f.gbuffer = makeGBuffer(w, h, i, normals, depth2);
    if (refEvery > 0 && i % refEvery == 0) f.reference = makeReference(w, h, i);
    f.view = makeView(i);
    f.projection = i % 2 ? makeReversedInfiniteProjection(w, h) : makeProjection(w, h);
    f.cut = (i % 3 == 2);
    frames.push_back(std::move(f));
  }
  return frames;
}

// Writes a G-buffer EXR with the given channels (each filled with `value`).
inline void writeExrWithChannels(const fs::path& p, int w, int h, const std::vector<std::pair<std::string, ExrPixelType>>& channels,
                                 float value = 0.5f) {
  std::vector<float> data(static_cast<size_t>(w) * h, value);
  std::vector<ExrChannel> list;
  for (const auto& [name, type] : channels) list.push_back({name, type, data.data()});
  writeExr(p, w, h, list);
}

// Runs f, expects an aor::InputError whose one-line message contains every part. Returns it.
template <typename F>
std::string expectInputError(F&& f, std::initializer_list<std::string> parts) {
  try {
    f();
  } catch (const InputError& e) {
    const std::string msg = e.what();
    if (std::getenv("AOR_PRINT_ERRORS")) std::printf("    message: %s\n", msg.c_str());
    for (const auto& part : parts) EXPECT_NE(msg.find(part), std::string::npos) << "\"" << part << "\" not in: " << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "not one line: " << msg;
    return msg;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected aor::InputError, got another exception: " << e.what();
    return {};
  }
  ADD_FAILURE() << "expected aor::InputError, nothing was thrown";
  return {};
}

}  // namespace aor::test

#define EXPECT_INPUT_ERROR(statement, ...)                                  \
  do {                                                                      \
    SCOPED_TRACE(#statement);                                               \
    ::aor::test::expectInputError([&] { statement; }, {__VA_ARGS__});       \
  } while (0)
