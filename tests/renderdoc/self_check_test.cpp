// The import's self-check (replay/import/self_check.h) on frames of two programs: rd_scene
// (Vulkan) and rd_gl_scene (OpenGL 3.3 core, rendered under xvfb-run; the import replays it
// headless). Correct imports pass with their figures in capture.json; each mistake made on
// purpose (a test-only fault, or a wrong --projection) exits 2 naming what disagreed and leaves
// no --out; OpenGL frames import upright, in the capture format's depth convention, to the
// capture the Vulkan frame of the same scene imports to.
#include <unistd.h>

#include "capture/capture.h"
#include "import_test_support.h"
#include "scene.h"

namespace aor::rdtest {
namespace {

const char* kVulkanCamera = "--view camera.view --projection camera.projection";
const char* kGlCamera = "--view SceneData.view --projection SceneData.projection";
constexpr int kWidth = 160, kHeight = 90;

// rd_gl_scene's frame 0 at 160x90: DIR/captures/0000.rdc, DIR/readback/0000.{depth,json}.
fs::path renderGlScene(const std::string& name, const std::string& format, const std::string& mode) {
  const fs::path dir = scratch(name);
  const Command c = run(fmt::format("xvfb-run -a {} --depth-format {} {} --size {}x{} --capture-dir {} --readback-dir {}",
                                    RD_GL_SCENE_EXE, format, mode, kWidth, kHeight, (dir / "captures").string(),
                                    (dir / "readback").string()));
  EXPECT_EQ(c.exitCode, 0) << c.output;
  return dir;
}

// Without a display, as on a CI runner: GL frames replay on the import's private Xvfb.
const char* kHeadless = "env -u DISPLAY -u EGL_PLATFORM";

Command import(const fs::path& sceneDir, const std::string& out, const std::string& arguments,
               const std::string& environment = kHeadless) {
  return aoreplay(fmt::format("import renderdoc {} --out {} {}", (sceneDir / "captures" / "0000.rdc").string(),
                              (sceneDir / out).string(), arguments),
                  environment);
}

nlohmann::json selfCheckOf(const fs::path& capture) {
  return readJson(capture / "capture.json").at("scene").at("frames").at(0).at("self_check");
}

void expectPassed(const Command& c, const fs::path& capture) {
  ASSERT_EQ(c.exitCode, 0) << c.output;
  EXPECT_NE(c.output.find(" 0 disagree"), std::string::npos) << c.output;
  const nlohmann::json check = selfCheckOf(capture);
  EXPECT_GE(check.at("matched").get<int>(), 16) << check;
  EXPECT_EQ(check.at("disagreed"), 0) << check;
  EXPECT_LT(check.at("depth_row_residual").get<double>(), 1e-4) << check;
  EXPECT_EQ(check.at("vertices_on_screen"), check.at("vertices")) << "the last box is whole on screen";
  std::printf("%s\n", c.output.substr(c.output.find("self-check:")).c_str());
}

// A failed import (a self-check, or the machine with exitCode 1): what it says, and no --out.
void expectCaught(const Command& c, const fs::path& out, const std::vector<std::string>& says, int exitCode = 2) {
  EXPECT_EQ(c.exitCode, exitCode) << c.output;
  for (const std::string& s : says) EXPECT_NE(c.output.find(s), std::string::npos) << s << "\n" << c.output;
  EXPECT_FALSE(fs::exists(out)) << "a failed import leaves no capture";
}

TEST(SelfCheck, VulkanFramePassesAndEachMistakeIsCaught) {
  const fs::path dir = renderScene(fmt::format("self-check-vk-{}", getpid()), "d24s8", false);
  expectPassed(import(dir, "ok", kVulkanCamera), dir / "ok");
  expectCaught(import(dir, "rows", std::string(kVulkanCamera) + " --test-only-fault rows"), dir / "rows",
               {"field \"--depth\": self-check failed: the imported depth disagrees with what the draw wrote",
                "its row order (flipped: yes)"});
  expectCaught(import(dir, "light", "--view camera.view --projection camera.light_projection"), dir / "light",
               {"field \"--projection\": self-check failed: camera.light_projection does not give the draw's "
                "vertices their clip-space z"});
}

TEST(SelfCheck, NotPossibleIsRefusedUnlessSkippedAndThenRecorded) {
  const fs::path dir = renderGlScene(fmt::format("self-check-points-{}", getpid()), "d32f", "--last-draw-points");
  expectCaught(import(dir, "refused", kGlCamera), dir / "refused",
               {"field \"--no-self-check\": self-check not possible: the draw's topology is PointList, not triangles"});
  const Command skipped = import(dir, "skipped", std::string(kGlCamera) + " --no-self-check");
  ASSERT_EQ(skipped.exitCode, 0) << skipped.output;
  EXPECT_NE(skipped.output.find("self-check: skipped (--no-self-check)"), std::string::npos) << skipped.output;
  EXPECT_EQ(selfCheckOf(dir / "skipped").at("skipped"), "--no-self-check");
}

struct GlCase {
  const char* format;       // rd_gl_scene's
  const char* vulkanFormat; // rd_scene's for the same storage
  const char* mode;         // rd_gl_scene's clip flags
  bool reversed;
  double quantum;
};

void PrintTo(const GlCase& c, std::ostream* os) { *os << c.format << " " << c.mode; }

class GlFrame : public ::testing::TestWithParam<GlCase> {};

// Depth per pixel of the two imports agree away from silhouettes: the same scene, rasterised by
// the same Mesa rasteriser through two APIs, in the capture's one convention.
void expectSameAsVulkan(const GBuffer& gl, const GBuffer& vk, double quantum) {
  size_t compared = 0, differ = 0;
  for (int y = 1; y + 1 < kHeight; ++y)
    for (int x = 1; x + 1 < kWidth; ++x) {
      const size_t i = size_t(y * kWidth + x);
      bool flat = true;  // no depth step around the pixel (silhouettes may round either way)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          flat = flat && std::abs(vk.depth[i + size_t(dy * kWidth + dx)] - vk.depth[i]) < 1e-3f;
      if (!flat) continue;
      ++compared;
      differ += std::abs(double(gl.depth[i]) - double(vk.depth[i])) > 2.0 * quantum + 1e-6;
    }
  EXPECT_GT(compared, 10000u);
  EXPECT_LE(differ, compared / 100) << differ << " of " << compared << " pixels differ from the Vulkan frame's";
}

// The imported frame against rd_gl_scene's own read-back: depth within half a quantum of
// glReadPixels' (rows turned top-down), the view within `viewTolerance` of scene.h's (0: bit for
// bit) and the projection scene.h's Vulkan one ([0, 1], y down).
void expectDepthLikeReadBack(const fs::path& dir, const Capture& capture, double quantum) {
  const GBuffer g = loadGBuffer(capture, 0);
  const std::vector<float> readBack = readBinary<float>(dir / "readback" / "0000.depth");  // GL rows: bottom first
  ASSERT_EQ(g.depth.size(), readBack.size());
  double worst = 0.0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      worst = std::max(worst, std::abs(double(g.depth[size_t(y * kWidth + x)]) -
                                       double(readBack[size_t((kHeight - 1 - y) * kWidth + x)])));
  EXPECT_LE(worst, quantum * 0.5 + 1e-7) << "the imported depth is glReadPixels' with its rows turned top-down";
}

void expectLikeReadBack(const fs::path& dir, const Capture& capture, double quantum, bool reversed,
                        float viewTolerance = 0.0f) {
  expectDepthLikeReadBack(dir, capture, quantum);
  const Camera camera = sceneCamera(0, kWidth, kHeight, reversed);
  if (viewTolerance == 0.0f) {
    EXPECT_TRUE(sameBits(capture.frames[0].view, camera.view));
  }
  for (int col = 0; col < 4; ++col)
    for (int row = 0; row < 4; ++row) {
      EXPECT_NEAR(capture.frames[0].view[col][row], camera.view[col][row], viewTolerance) << "view[" << col << "][" << row << "]";
      EXPECT_NEAR(capture.frames[0].projection[col][row], camera.projection[col][row],
                  std::max(1e-6 * std::abs(camera.projection[col][row]), double(viewTolerance)))
          << "projection[" << col << "][" << row << "]";
    }
}

TEST_P(GlFrame, ImportsUprightInTheCaptureConventionAndPassesTheCheck) {
  const GlCase& c = GetParam();
  const std::string name = fmt::format("self-check-gl-{}-{}{}", c.format, c.mode[0] ? "clip-control" : "default",
                                       c.reversed ? "-reversed" : "");
  const fs::path dir = renderGlScene(name, c.format, c.mode);
  const Command r = import(dir, "imported", kGlCamera);
  expectPassed(r, dir / "imported");
  EXPECT_NE(r.output.find("OpenGL, replayed on a private X display (Xvfb :"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("rows bottom-up, flipped"), std::string::npos) << r.output;

  const Capture capture = loadCapture(dir / "imported");
  expectLikeReadBack(dir, capture, c.quantum, c.reversed);
  const GBuffer g = loadGBuffer(capture, 0);

  const fs::path vk = renderScene(name + "-vulkan", c.vulkanFormat, c.reversed);
  const Command v = import(vk, "imported", kVulkanCamera);
  ASSERT_EQ(v.exitCode, 0) << v.output;
  const Capture vkCapture = loadCapture(vk / "imported");
  expectSameAsVulkan(g, loadGBuffer(vkCapture, 0), c.quantum);
}

INSTANTIATE_TEST_SUITE_P(
    Formats, GlFrame,
    ::testing::Values(GlCase{"d16", "d16", "", false, 1.0 / 65535}, GlCase{"d24", "x8d24", "", false, 1.0 / 16777215},
                      GlCase{"d24s8", "d24s8", "", false, 1.0 / 16777215}, GlCase{"d32f", "d32", "", false, 6e-8},
                      GlCase{"d32fs8", "d32s8", "", false, 6e-8},
                      GlCase{"d24s8", "d24s8", "--clip-control", false, 1.0 / 16777215},
                      GlCase{"d32f", "d32", "--clip-control --reversed", true, 6e-8}),
    [](const auto& info) {
      std::string mode = info.param.mode[0] ? (info.param.reversed ? "_clip_control_reversed" : "_clip_control") : "";
      return std::string(info.param.format) + mode;
    });

// A frame that ends with a full-screen composite (depth test and writes off, depth target bound),
// as Godot 3's do: the default event is the scene's last depth-writing draw, not the composite.
TEST(SelfCheck, TheDefaultEventPassesOverAFinalCompositeToTheScenesLastDraw) {
  const fs::path dir = renderGlScene(fmt::format("self-check-final-copy-{}", getpid()), "d24s8", "--final-copy");
  const Command r = import(dir, "imported", kGlCamera);
  expectPassed(r, dir / "imported");
  EXPECT_NE(r.output.find("event 26 glDrawArrays(): last draw that tests and writes depth (1 later draw with depth test or "
                          "writes off passed over)"),
            std::string::npos)
      << r.output;
  const Command composite = import(dir, "composite", std::string(kGlCamera) + " --event 30");
  EXPECT_EQ(composite.exitCode, 2) << "the composite itself has no camera block: " << composite.output;
}

// Issue 46 item 2 (first part): GL default-block uniforms, which RenderDoc reflects as the block
// $Globals without a buffer, are read like push constants and named as what they are. rd_gl_scene's
// `model` is one (the identity, so as a --view it gives the identity).
TEST(SelfCheck, GlDefaultBlockUniformsAreRead) {
  const fs::path dir = renderGlScene(fmt::format("self-check-gl-globals-{}", getpid()), "d32f", "");
  const Command listing = import(dir, "listing", "--view nosuch.view --projection SceneData.projection");
  EXPECT_NE(listing.output.find("$Globals [vertex shader, default-block uniforms: model (mat4)]"), std::string::npos)
      << listing.output;
  const Command r = import(dir, "imported", "--view '$Globals.model' --projection SceneData.projection");
  expectPassed(r, dir / "imported");
  EXPECT_NE(r.output.find("view: $Globals.model (vertex shader, column-major, default-block uniforms)"), std::string::npos)
      << r.output;
  const nlohmann::json capture = readJson(dir / "imported" / "capture.json");
  const nlohmann::json identity = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  EXPECT_EQ(capture.at("frames").at(0).at("view"), identity);
}

// Each mistake the import once made on GL frames (README's "The self-check"), made on purpose.
TEST(SelfCheck, EachGlMistakeIsCaught) {
  const fs::path dir = renderGlScene(fmt::format("self-check-gl-faults-{}", getpid()), "d24s8", "");
  const std::string fault = std::string(kGlCamera) + " --test-only-fault ";
  const std::string disagrees = "field \"--depth\": self-check failed: ";
  expectCaught(import(dir, "rows", fault + "rows"), dir / "rows", {disagrees, "its row order (flipped: no)"});
  expectCaught(import(dir, "d24", fault + "d24-low-bits"), dir / "d24", {disagrees, "(OpenGL D24S8)"});
  expectCaught(import(dir, "clip", fault + "clip-z"), dir / "clip", {disagrees, "(clip z in [0, 1])"});
  expectCaught(import(dir, "light", "--view SceneData.view --projection SceneData.light_projection"), dir / "light",
               {"field \"--projection\": self-check failed: SceneData.light_projection does not give"});
  const fs::path upperLeft = renderGlScene(fmt::format("self-check-gl-clip-control-{}", getpid()), "d32f",
                                           "--clip-control");
  expectCaught(import(upperLeft, "rows", fault + "rows"), upperLeft / "rows", {disagrees, "(flipped: no)"});
}

// Issue 46: a GL 3.3 core frame as engines make them, imported with no display: the camera in
// default-block uniforms ($Globals), the scene in a D24S8 FBO, a post-processing pass into the
// window after it, with GL's clip conventions and with glClipControl(GL_UPPER_LEFT,
// GL_ZERO_TO_ONE); the capture then replays under the validation layer without a message.
class GlGlobalsCamera : public ::testing::TestWithParam<bool> {};

TEST_P(GlGlobalsCamera, ImportsHeadlessLikeTheProgramsReadBackAndReplaysValidated) {
  const bool clipControl = GetParam();
  const fs::path dir = renderGlScene(fmt::format("gl-globals-post-{}-{}", clipControl, getpid()), "d24s8",
                                     std::string("--camera globals --post-process") + (clipControl ? " --clip-control" : ""));
  const Command r = import(dir, "imported", "--view '$Globals.view' --projection '$Globals.projection'");
  expectPassed(r, dir / "imported");
  EXPECT_NE(r.output.find("OpenGL, replayed on a private X display (Xvfb :"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("(1 later draw with depth test or writes off passed over)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("D24S8 160x90"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("adjusted: clip z in [-1, 1]") == std::string::npos, clipControl) << r.output;
  expectLikeReadBack(dir, loadCapture(dir / "imported"), 1.0 / 16777215, false);

  const Command replay = aoreplay(fmt::format("run {} --validate --no-images --out {}", (dir / "imported").string(),
                                              (dir / "run").string()),
                                  kHeadless);
  EXPECT_EQ(replay.exitCode, 0) << replay.output;
  EXPECT_NE(replay.output.find("validation: 0 messages"), std::string::npos) << replay.output;
}

INSTANTIATE_TEST_SUITE_P(ClipConventions, GlGlobalsCamera, ::testing::Bool(),
                         [](const auto& info) { return info.param ? "clip_control_upper_left_zero_to_one" : "gl_default"; });

// One default-block view_projection, factored as a Vulkan program's is (--view-projection).
TEST(SelfCheck, GlCombinedViewProjectionIsFactored) {
  const fs::path dir = renderGlScene(fmt::format("gl-combined-{}", getpid()), "d32f", "--camera combined --post-process");
  const Command r = import(dir, "imported", "--view-projection '$Globals.view_projection'");
  expectPassed(r, dir / "imported");
  EXPECT_NE(r.output.find("view-projection: $Globals.view_projection (vertex shader, column-major, default-block "
                          "uniforms): factored into a perspective projection and a rigid view"),
            std::string::npos)
      << r.output;
  expectLikeReadBack(dir, loadCapture(dir / "imported"), 6e-8, false, 2e-6f);
}

// The window's own depth (GLX's D24S8 back buffer), named with its whole 64-bit resource id
// (it was printed cut to 32 bits, as a negative number).
TEST(SelfCheck, GlDefaultFramebufferDepthImports) {
  const fs::path dir = renderGlScene(fmt::format("gl-default-framebuffer-{}", getpid()), "d24s8", "--default-framebuffer");
  const Command r = import(dir, "imported", kGlCamera);
  expectPassed(r, dir / "imported");
  const nlohmann::json depth = readJson(dir / "imported" / "capture.json").at("scene").at("frames").at(0).at("depth");
  ASSERT_TRUE(depth.at("id").is_number_unsigned()) << depth;
  EXPECT_GT(depth.at("id").get<uint64_t>(), uint64_t(UINT32_MAX)) << "RenderDoc's back-buffer ids are above 2^32";
  EXPECT_NE(r.output.find(fmt::format("depth: {} (id {}), D24S8 160x90", depth.at("resource").get<std::string>(),
                                      depth.at("id").get<uint64_t>())),
            std::string::npos)
      << r.output;
  expectLikeReadBack(dir, loadCapture(dir / "imported"), 1.0 / 16777215, false);
}

// glDepthRange folded into the projection: the depth as drawn, the camera described as it is
// (near 0.1, far 40), and [1, 0] (reversed by range) as scene.h's reversed projection.
TEST(SelfCheck, GlDepthRangesAreFoldedIntoTheProjection) {
  const fs::path dir = renderGlScene(fmt::format("gl-depth-range-{}", getpid()), "d24s8", "--depth-range 0.25,0.75");
  const Command r = import(dir, "imported", kGlCamera);
  expectPassed(r, dir / "imported");
  EXPECT_NE(r.output.find("camera: perspective, standard depth, near 0.1, far 40,"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("adjusted: viewport depth range [0.25, 0.75]: folded into the projection's depth row"),
            std::string::npos)
      << r.output;
  expectDepthLikeReadBack(dir, loadCapture(dir / "imported"), 1.0 / 16777215);

  const fs::path reversed = renderGlScene(fmt::format("gl-depth-range-reversed-{}", getpid()), "d32f", "--depth-range 1,0");
  const Command rr = import(reversed, "imported", kGlCamera);
  expectPassed(rr, reversed / "imported");
  EXPECT_NE(rr.output.find("camera: perspective, reversed depth, near 0.1, far 40,"), std::string::npos) << rr.output;
  // One float rounding of terms near 1 in the folded depth row: 1e-8 off its 0.0025 entry.
  expectLikeReadBack(reversed, loadCapture(reversed / "imported"), 6e-8, true, 1e-7f);
}

// Without a display and without Xvfb: exit 2 naming the package, nothing at --out. An Xvfb that
// does not come up: its own words, exit 1 (the machine, not the capture), nothing at --out.
TEST(SelfCheck, GlWithoutDisplayOrXvfbSaysWhatToInstall) {
  const fs::path dir = renderGlScene(fmt::format("gl-no-xvfb-{}", getpid()), "d32f", "");
  const fs::path bin = dir / "bin";
  fs::create_directories(bin);
  expectCaught(import(dir, "missing", kGlCamera, fmt::format("{} PATH={}", kHeadless, bin.string())), dir / "missing",
               {"0000.rdc: an OpenGL capture replays on an X display, DISPLAY is unset and Xvfb is not installed: "
                "install Debian's xvfb (apt-get install xvfb)"});
  std::ofstream(bin / "Xvfb") << "#!/bin/sh\necho 'Fatal server error: no screens found' >&2\nexit 1\n";
  fs::permissions(bin / "Xvfb", fs::perms::owner_all);
  expectCaught(import(dir, "broken", kGlCamera, fmt::format("{} PATH={}:/usr/bin:/bin", kHeadless, bin.string())),
               dir / "broken",
               {"Xvfb did not start a display (it has 10 s); its last output: Fatal server error: no screens found"}, 1);
}

}  // namespace
}  // namespace aor::rdtest
