#include "bench_capture.h"

#include <fmt/format.h>

namespace aor::bench {
namespace fs = std::filesystem;

namespace {

GBuffer resampleNearest(const GBuffer& in, int width, int height) {
  GBuffer out;
  out.width = width;
  out.height = height;
  out.depth.resize(size_t(width) * size_t(height));
  if (!in.normals.empty()) out.normals.resize(out.depth.size() * 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      size_t src = size_t((y * in.height) / height) * size_t(in.width) + size_t((x * in.width) / width);
      size_t dst = size_t(y) * size_t(width) + size_t(x);
      out.depth[dst] = in.depth[src];
      for (size_t c = 0; c < 3 && !in.normals.empty(); ++c) out.normals[3 * dst + c] = in.normals[3 * src + c];
    }
  return out;
}

}  // namespace

Capture resampledCapture(const fs::path& source, int width, int height, int frames, const fs::path& cacheDir) {
  Capture original = loadCapture(source);
  if (original.width == width && original.height == height) return original;
  fs::path folder = cacheDir / fmt::format("{}-{}x{}-{}f", original.name, width, height, frames);
  if (fs::exists(folder / "capture.json")) return loadCapture(folder);
  std::vector<CaptureFrameData> data;
  for (int i = 0; i < frames; ++i) {
    const auto& f = original.frames[size_t(i)];
    data.push_back({resampleNearest(loadGBuffer(original, i), width, height), std::nullopt, f.view, f.projection, f.cut});
  }
  fs::path staging = folder;
  staging += ".partial";
  fs::remove_all(staging);
  // The geometry is world space, the same at every size: carried over for the techniques that trace it.
  std::optional<CaptureGeometry> geometry;
  if (original.geometry) geometry = loadGeometry(original);
  writeCapture(staging, width, height, data, original.scene, geometry ? &*geometry : nullptr);
  fs::rename(staging, folder);  // a half-written cache never looks complete
  return loadCapture(folder);
}

}  // namespace aor::bench
