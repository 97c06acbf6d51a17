#pragma once
// A capture's scene geometry (format 1.1, captures/FORMAT.md "Geometry"): world-space triangles
// from a Wavefront OBJ, static over the capture, for techniques that trace rays (rtao). Read with
// tinyobjloader; the limits below are checked line by line so a bad file is reported by its line.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace aor {

// The most triangles a capture's geometry may hold (after polygons are split into triangles).
inline constexpr uint64_t kMaxGeometryTriangles = uint64_t(1) << 24;

struct CaptureGeometry {
  std::vector<float> positions;  // xyz per vertex, world space
  std::vector<uint32_t> indices; // three per triangle, into positions / 3
  size_t triangleCount() const { return indices.size() / 3; }
  size_t vertexCount() const { return positions.size() / 3; }
};

// Reads `path` (`display` names it in errors). Throws InputError "<display>: line N: ..." for
// malformed statements, coordinates that are not finite 32-bit floats, face indices out of range,
// more than kMaxGeometryTriangles triangles, or a file without any triangle.
CaptureGeometry readObjGeometry(const std::filesystem::path& path, const std::string& display);

// The OBJ text of `geometry`: `v` lines with each float's shortest exact decimal form, then `f`
// lines (1-based), so reading it back gives the same floats; deterministic.
std::string objText(const CaptureGeometry& geometry, const std::string& comment);

}  // namespace aor
