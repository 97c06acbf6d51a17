#pragma once
// Synthetic capture generator (`aoreplay capture`). Scenes are exact geometry ray traced with
// Embree on the CPU, so G-buffers and the reference visibility come from the same surfaces.
// Output is deterministic for the same options (fixed seeds, no thread-order dependence).
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace aor::gen {

struct GeneratorOptions {
  std::string scene = "boxes";  // one of sceneNames()
  int width = 320;
  int height = 180;
  int frames = 24;
  std::string path = "orbit";   // orbit | dolly | static | cut | strafe
  int referenceSpp = 0;         // 0: no reference EXRs; else cosine-weighted rays per pixel
  std::optional<float> radius;  // AO radius in world units; default: the scene's own
  bool reversedZ = false;       // reversed depth (near = 1, far = 0)
  bool infiniteFar = false;     // infinite far plane
  bool writeNormals = true;     // false: depth-only capture (normals reconstructed on replay)
  // Second depth layer (`depth2`): per pixel the nearest surface at least depth2Separation world
  // units behind layer 0 along the pixel's ray, found by peeling (tracing on from there).
  bool depth2 = false;
  double depth2Separation = 0.01;  // world units; the deep G-buffer papers' minimum separation for AO
  float verticalFovDegrees = 60.0f;
  uint64_t seed = 1;
  std::function<void(int done, int total)> progress;  // called from the calling thread only
};

std::vector<std::string> sceneNames();
std::vector<std::string> pathNames();

// Writes a complete capture to `out` (capture folder). Throws aor::InputError for bad options.
void generateCapture(const GeneratorOptions& options, const std::filesystem::path& out);

}  // namespace aor::gen
