#pragma once
// Shared by the GPU tests: one validated Vulkan context per test program (zero validation
// messages is asserted at exit), small captures made on the fly, and running the aoreplay binary.
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "capture/capture.h"
#include "replay_loop/replayer.h"
#include "techniques/gtao/gtao_settings.h"
#include "techniques/registry.h"
#include "vk/context.h"

namespace aor::test {

// Lavapipe context with validation + synchronization validation, created on first use.
VulkanContext& validatedContext();

std::filesystem::path scratchDir(const std::string& name);  // fresh folder under the build tree, private to the running test
std::string readText(const std::filesystem::path& file);    // the whole file, bytes as they are

// Generated with the project's generator once per test program (cached by name).
std::filesystem::path generatedCapture(const std::string& scene, const std::string& path, int width, int height,
                                       int frames, bool normals = true);

// Flat floor y = 0 seen from a camera `heightAboveFloor` up, pitched down by `pitchDegrees`;
// depth computed analytically per pixel (sky where the ray misses).
struct PlaneCaptureOptions {
  int width = 64, height = 36;
  float pitchDegrees = 30.0f;
  float heightAboveFloor = 1.0f;
  float verticalFovDegrees = 60.0f;
  bool reversedZ = false;
  bool infiniteFar = false;
  bool normals = true;
};
std::filesystem::path planeCapture(const std::string& name, const PlaneCaptureOptions& options);

struct ReplayedFrames {
  ReplayResult result;
  std::vector<FrameOutput> frames;
};
ReplayedFrames replay(const std::filesystem::path& capture, const Settings& settings, int begin = 0, int end = -1,
                      bool keepHistoryOnCut = false);
// `gtao` with these values (techniques/gtao/gtao_settings.h).
inline ReplayedFrames replay(const std::filesystem::path& capture, const GtaoSettings& settings, int begin = 0,
                             int end = -1, bool keepHistoryOnCut = false) {
  return replay(capture, settingsOf(gtaoTechnique(), settings), begin, end, keepHistoryOnCut);
}
// As `aoreplay run CAPTURE --technique T --set A --set B ... --frames begin:end` resolves settings:
// the technique's default preset, the capture's scene.ao_radius, then the assignments in order.
ReplayedFrames replayWithSettings(const std::filesystem::path& capture, const std::string& technique,
                                  const std::vector<std::string>& assignments, int begin = 0, int end = -1);

struct CommandResult {
  int exitCode = -1;
  std::string output;  // stdout and stderr
};
// Runs the aoreplay binary with `arguments` (already quoted) and optional environment prefix.
CommandResult runAoreplay(const std::string& arguments, const std::string& environment = "");

// The shipped example user techniques (examples/user_techniques/*/technique.json), absolute.
std::vector<std::string> exampleTechniqueFiles();
// What the suites that cover every technique run: each built-in's name, then each example's file
// (a --technique value either way).
std::vector<std::string> coveredTechniques();
// A test name for a --technique value: the technique's name.
std::string techniqueTestName(const std::string& techniqueArgument);

bool bitIdentical(const std::vector<float>& a, const std::vector<float>& b);

// Default settings without the spatial and temporal passes: the read-back is GTAO's own output.
GtaoSettings gtaoOnly();
// The screen-space reference technique with the integral's values of `settings`.
Settings referenceOf(const GtaoSettings& settings);

// Index of the first frame after frame 0 marked `cut`, -1 when none is.
int cutFrame(const Capture& capture);

}  // namespace aor::test
