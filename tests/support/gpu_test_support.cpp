#include "gpu_test_support.h"

#include "core/input_error.h"

#include <algorithm>
#include <cctype>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>

#include <unistd.h>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include "generator/generator.h"

namespace aor::test {
namespace fs = std::filesystem;

namespace {

// Destroys the shared context after all tests and fails the program if validation said anything.
struct ContextHolder {
  VulkanContext vk;
  bool created = false;
  ~ContextHolder() {
    if (!created) return;
    destroyContext(vk);
    size_t messages = vk.validationMessageCount();
    if (messages) {
      std::fprintf(stderr, "FAILED: %zu validation message(s) during the GPU tests\n", messages);
      std::_Exit(1);
    }
  }
};

ContextHolder& holder() {
  static ContextHolder h;
  return h;
}

glm::mat4 vulkanProjection(float fovDegrees, float aspect, bool reversed, bool infinite) {
  float f = 1.0f / std::tan(glm::radians(fovDegrees) * 0.5f);
  float n = 0.05f, far = 200.0f;
  glm::mat4 p(0.0f);
  p[0][0] = f / aspect;
  p[1][1] = -f;  // Vulkan NDC y points down
  p[2][3] = -1.0f;
  if (!reversed && !infinite) { p[2][2] = far / (n - far); p[3][2] = n * far / (n - far); }
  if (!reversed && infinite) { p[2][2] = -1.0f; p[3][2] = -n; }
  if (reversed && !infinite) { p[2][2] = n / (far - n); p[3][2] = n * far / (far - n); }
  if (reversed && infinite) { p[2][2] = 0.0f; p[3][2] = n; }
  return p;
}

}  // namespace

VulkanContext& validatedContext() {
  auto& h = holder();
  if (!h.created) {
    createContext(h.vk, {"", true});
    h.created = true;
  }
  return h.vk;
}

std::string readText(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// CTest runs every test as its own process, two or more at once: a folder per test keeps one test
// from emptying a folder another is still reading.
fs::path scratchDir(const std::string& name) {
  const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string owner = test ? fmt::format("{}.{}", test->test_suite_name(), test->name()) : "no-test";
  std::replace(owner.begin(), owner.end(), '/', '_');
  fs::path dir = fs::path(AOR_BINARY_DIR) / "test-scratch" / owner / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

fs::path generatedCapture(const std::string& scene, const std::string& path, int width, int height, int frames,
                          bool normals) {
  fs::path dir = fs::path(AOR_BINARY_DIR) / "test-captures" /
                 fmt::format("{}-{}-{}x{}-{}{}", scene, path, width, height, frames, normals ? "" : "-depthonly");
  if (fs::exists(dir / "capture.json")) return dir;
  gen::GeneratorOptions o;
  o.scene = scene;
  o.path = path;
  o.width = width;
  o.height = height;
  o.frames = frames;
  o.writeNormals = normals;
  // CTest runs tests as parallel processes: generate privately, then publish with one rename.
  fs::path mine = dir.string() + fmt::format(".gen-{}", getpid());
  gen::generateCapture(o, mine);
  std::error_code alreadyThere;
  fs::rename(mine, dir, alreadyThere);
  if (alreadyThere) fs::remove_all(mine);
  return dir;
}

fs::path planeCapture(const std::string& name, const PlaneCaptureOptions& o) {
  fs::path dir = fs::path(AOR_BINARY_DIR) / "test-captures" / name;
  float aspect = float(o.width) / float(o.height);
  glm::mat4 projection = vulkanProjection(o.verticalFovDegrees, aspect, o.reversedZ, o.infiniteFar);
  glm::vec3 eye(0.0f, o.heightAboveFloor, 0.0f);
  float pitch = glm::radians(o.pitchDegrees);
  glm::vec3 forward(0.0f, -std::sin(pitch), -std::cos(pitch));
  glm::mat4 view = glm::lookAtRH(eye, eye + forward, glm::vec3(0, 1, 0));
  glm::dmat4 invViewProj = glm::inverse(glm::dmat4(projection) * glm::dmat4(view));

  CaptureFrameData frame;
  frame.view = view;
  frame.projection = projection;
  auto& g = frame.gbuffer;
  g.width = o.width;
  g.height = o.height;
  size_t pixels = size_t(o.width) * size_t(o.height);
  g.depth.assign(pixels, o.reversedZ ? 0.0f : 1.0f);
  if (o.normals) g.normals.assign(pixels * 3, 0.0f);
  for (int y = 0; y < o.height; ++y)
    for (int x = 0; x < o.width; ++x) {
      glm::dvec4 ndc((2.0 * x + 1.0) / o.width - 1.0, (2.0 * y + 1.0) / o.height - 1.0, 0.5, 1.0);
      glm::dvec4 world = invViewProj * ndc;
      glm::dvec3 dir = glm::normalize(glm::dvec3(world) / world.w - glm::dvec3(eye));
      size_t i = size_t(y) * size_t(o.width) + size_t(x);
      if (dir.y >= -1e-9) continue;  // sky
      double t = -double(eye.y) / dir.y;
      glm::dvec4 clip = glm::dmat4(projection) * glm::dmat4(view) * glm::dvec4(glm::dvec3(eye) + t * dir, 1.0);
      g.depth[i] = float(clip.z / clip.w);
      if (o.normals) g.normals[3 * i + 1] = 1.0f;
    }
  fs::path mine = dir.string() + fmt::format(".gen-{}", getpid());
  writeCapture(mine, o.width, o.height, {frame}, {{"ao_radius", 1.0}});
  fs::remove_all(dir);
  fs::rename(mine, dir);
  return dir;
}

ReplayedFrames replay(const fs::path& capturePath, const Settings& settings, int begin, int end, bool keepHistoryOnCut) {
  Capture capture = loadCapture(capturePath);
  ReplayOptions options(settings);
  options.frameBegin = begin;
  options.frameEnd = end;
  options.keepHistoryOnCut = keepHistoryOnCut;
  ReplayedFrames out;
  out.result = replayCapture(validatedContext(), capture, options, [&](const FrameOutput& f) { out.frames.push_back(f); });
  return out;
}

ReplayedFrames replayWithSettings(const fs::path& capturePath, const std::string& technique,
                                  const std::vector<std::string>& assignments, int begin, int end) {
  Capture capture = loadCapture(capturePath);
  return replay(capturePath, resolveSettings(findTechnique(technique), capture, "", assignments), begin, end);
}

CommandResult runAoreplay(const std::string& arguments, const std::string& environment) {
  std::string command = fmt::format("{} {} {} 2>&1", environment, AOR_EXE, arguments);
  CommandResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer;
  while (size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe)) result.output.append(buffer.data(), n);
  int status = pclose(pipe);
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

bool bitIdentical(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

Settings referenceOf(const GtaoSettings& settings) { return settingsOf(referenceTechnique(), settings); }

GtaoSettings gtaoOnly() {
  GtaoSettings s;
  s.spatial = 0;
  s.temporal = 0;
  return s;
}

int cutFrame(const Capture& capture) {
  for (size_t i = 1; i < capture.frames.size(); ++i)
    if (capture.frames[i].cut) return int(i);
  return -1;
}

// User techniques' compiled shaders go to the build tree, never to the user's ~/.cache; children
// (runAoreplay) inherit it.
const bool kTestShaderCache = [] {
  ::setenv("AOREPLAY_SHADER_CACHE", (std::filesystem::path(AOR_BINARY_DIR) / "test-scratch" / "shader-cache").c_str(), 0);
  return true;
}();

std::vector<std::string> exampleTechniqueFiles() {
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(AOR_SOURCE_DIR) / "examples" / "user_techniques"))
    if (std::filesystem::exists(entry.path() / "technique.json")) files.push_back((entry.path() / "technique.json").string());
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<std::string> coveredTechniques() {
  std::vector<std::string> out;
  for (const Technique* t : userTechniques())
    if (t->file.empty()) out.push_back(t->name);
  for (const auto& file : exampleTechniqueFiles()) out.push_back(file);
  return out;
}

std::string techniqueTestName(const std::string& techniqueArgument) {
  try {
    return findTechnique(techniqueArgument).name;
  } catch (const InputError&) {  // a broken example: its tests run (and fail with the error) under its folder's name
    std::string name = std::filesystem::path(techniqueArgument).parent_path().filename().string();
    for (char& c : name)
      if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return name;
  }
}

}  // namespace aor::test
