#pragma once
// Capture format 1.1 (captures/FORMAT.md; version 1 files read unchanged): a folder with capture.json and EXR G-buffers.
// Reading validates everything up front (JSON, matrices, paths, EXR headers of every frame), so a
// replay never fails half-way through on a bad file. Errors are aor::InputError.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <nlohmann/json.hpp>

#include "core/input_error.h"
#include "core/json_input.h"
#include "capture/obj_geometry.h"

namespace aor {

// The most frames a capture may have (captures/FORMAT.md).
inline constexpr int kMaxCaptureFrames = 100'000;
// capture.json holds at most kMaxCaptureFrames frames (and no array longer than that) in at most
// 256 MiB: a capture of 10^5 frames as writeCapture writes it is about 100 MB.
inline constexpr JsonLimits kCaptureJsonLimits{std::uint64_t(256) << 20, kMaxCaptureFrames, 128};
// scene.ao_radius must lie in the range of the `radius` setting it becomes (technique_api/parameters.cpp;
// tests/replay_loop checks that the two agree).
inline constexpr double kMinAoRadius = 1e-6;
inline constexpr double kMaxAoRadius = 1e7;

struct CaptureFrame {
  std::filesystem::path gbuffer;                  // absolute, inside the capture folder
  std::optional<std::filesystem::path> reference; // absolute, inside the capture folder
  glm::mat4 view{1.0f};                           // world -> view
  glm::mat4 projection{1.0f};                     // view -> clip, perspective, depth [0,1]
  bool cut = false;                               // camera cut before this frame
};

struct Capture {
  std::filesystem::path folder;
  std::string name;  // folder name, used for default output paths
  int width = 0;
  int height = 0;
  std::vector<CaptureFrame> frames;
  nlohmann::json scene = nlohmann::json::object();
  // Channel layout, identical in every frame (checked when loading).
  bool hasNormals = false;
  bool hasDepth2 = false;
  // Format 1.1: the scene's world-space triangles (an OBJ inside the folder), when the capture has them.
  std::optional<std::filesystem::path> geometry;  // absolute, inside the capture folder
};

// Parses capture.json in `folder` and checks every referenced EXR header.
Capture loadCapture(const std::filesystem::path& folder);

struct GBuffer {
  int width = 0, height = 0;
  std::vector<float> depth;    // width*height, row 0 at the top
  std::vector<float> normals;  // width*height*3 (xyz interleaved, world space); empty without normals
  std::vector<float> depth2;   // width*height; empty without a second layer
};

// The files a replay of `capture` reads: capture.json and each distinct EXR (outputs must not overwrite them).
std::vector<std::filesystem::path> captureFiles(const Capture& capture);

GBuffer loadGBuffer(const Capture& capture, int frame);
// Reference visibility (width*height, in [0,1]); std::nullopt when the frame has none.
std::optional<std::vector<float>> loadReference(const Capture& capture, int frame);
// The capture's geometry, read and checked (obj_geometry.h); InputError when it has none.
CaptureGeometry loadGeometry(const Capture& capture);

// Writing, used by the generator. writeCapture replaces `folder` by the rules of every output
// folder (core/output_directory.h): files go to a staging folder swapped in only when
// everything was written, and only an earlier capture is ever replaced.
struct CaptureFrameData {
  GBuffer gbuffer;
  std::optional<std::vector<float>> reference;
  glm::mat4 view{1.0f};
  glm::mat4 projection{1.0f};
  bool cut = false;
};
// With `geometry`, the capture is version 1.1 and the triangles are written as scene.obj.
void writeCapture(const std::filesystem::path& folder, int width, int height,
                  const std::vector<CaptureFrameData>& frames, const nlohmann::json& scene,
                  const CaptureGeometry* geometry = nullptr);
// The files alone, into `folder` (empty or new; e.g. an OutputDirectory's staging folder).
void writeCaptureFiles(const std::filesystem::path& folder, int width, int height,
                       const std::vector<CaptureFrameData>& frames, const nlohmann::json& scene,
                       const CaptureGeometry* geometry = nullptr);

}  // namespace aor
