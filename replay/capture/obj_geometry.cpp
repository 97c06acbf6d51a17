#include "capture/obj_geometry.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <cstring>
#include <iterator>

#include <fmt/format.h>
#include <tiny_obj_loader.h>

#include "core/input_error.h"

namespace aor {
namespace {

// The line-numbered checks tinyobjloader does not make (it reads "nan" as 0, reports indices out
// of range against the file's last line, and has no size limit): one pass over the statements
// that make geometry, `v` and `f`, before tinyobjloader reads the file.
class ObjLimits {
 public:
  explicit ObjLimits(const std::string& display) : display_(display) {}

  void scan(std::istream& in) {
    std::string line;
    uint64_t number = 0;
    while (std::getline(in, line)) {
      ++number;
      const char* p = line.c_str();
      p += std::strspn(p, " \t");
      if (p[0] == 'v' && (p[1] == ' ' || p[1] == '\t')) vertex(p + 2, number);
      else if (p[0] == 'f' && (p[1] == ' ' || p[1] == '\t')) face(p + 2, number);
    }
    // A forward reference is legal OBJ when the vertex comes later; the first that never does is
    // reported with its own line.
    for (const auto& f : forward_)
      if (f.index > vertices_)
        fail(f.line, fmt::format("face index {} is past the last vertex (the file has {} vertices)", f.index, vertices_));
    if (triangles_ == 0) fail(number, "the file has no triangle (no `f` statement with three or more vertices)");
  }

 private:
  struct ForwardReference {
    uint64_t line;
    long long index;
  };

  [[noreturn]] void fail(uint64_t line, const std::string& problem) const {
    throw InputError(display_, std::nullopt, "", fmt::format("line {}: {}", line, problem));
  }

  void vertex(const char* p, uint64_t line) {
    static const char* const kAxes[] = {"x", "y", "z"};
    for (const char* axis : kAxes) {
      p += std::strspn(p, " \t");
      char* end = nullptr;
      double value = std::strtod(p, &end);
      if (end == p) fail(line, fmt::format("vertex coordinate {} is missing or not a number", axis));
      if (!std::isfinite(value) || std::abs(value) > double(std::numeric_limits<float>::max()))
        fail(line, fmt::format("vertex coordinate {} = {} is not a finite 32-bit float", axis, std::string(p, size_t(end - p))));
      p = end;
    }
    ++vertices_;
  }

  void face(const char* p, uint64_t line) {
    int corners = 0;
    while (true) {
      p += std::strspn(p, " \t\r");
      if (*p == '\0' || *p == '#') break;
      char* end = nullptr;
      long long index = std::strtoll(p, &end, 10);
      if (end == p) fail(line, "face corner is not a vertex index");
      if (index == 0) fail(line, "face index 0 (OBJ indices start at 1)");
      if (index < 0 && -index > vertices_)
        fail(line, fmt::format("face index {} reaches before the first vertex ({} vertices so far)", index, vertices_));
      if (index > std::numeric_limits<int>::max()) fail(line, fmt::format("face index {} is out of range", index));
      if (index > vertices_) forward_.push_back({line, index});
      p = end + std::strcspn(end, " \t\r");  // skip /texcoord/normal
      ++corners;
    }
    if (corners < 3) fail(line, fmt::format("a face needs at least 3 vertices, this one has {}", corners));
    triangles_ += uint64_t(corners - 2);
    if (triangles_ > kMaxGeometryTriangles)
      fail(line, fmt::format("more than {} triangles, the limit", kMaxGeometryTriangles));
  }

 private:
  std::string display_;
  long long vertices_ = 0;
  uint64_t triangles_ = 0;
  std::vector<ForwardReference> forward_;
};

}  // namespace

CaptureGeometry readObjGeometry(const std::filesystem::path& path, const std::string& display) {
  {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(display, std::nullopt, "", "cannot open the file");
    ObjLimits limits(display);
    limits.scan(in);
  }
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  // No material search path: a capture's geometry is triangles only, a `mtllib` is ignored.
  if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, path.c_str(), nullptr, true))
    throw InputError(display, std::nullopt, "", "cannot parse OBJ: " + err);
  CaptureGeometry g;
  g.positions.assign(attrib.vertices.begin(), attrib.vertices.end());
  const size_t vertices = g.vertexCount();
  for (const auto& shape : shapes) {
    size_t first = 0;
    for (const auto corners : shape.mesh.num_face_vertices) {
      for (size_t k = 0; k < corners; ++k) {
        int index = shape.mesh.indices[first + k].vertex_index;
        if (index < 0 || size_t(index) >= vertices)  // the scan's checks make this unreachable
          throw InputError(display, std::nullopt, "", fmt::format("face index {} out of range", index + 1));
        g.indices.push_back(uint32_t(index));
      }
      first += corners;
    }
  }
  return g;
}

std::string objText(const CaptureGeometry& geometry, const std::string& comment) {
  std::string text = "# " + comment + "\n";
  text.reserve(geometry.positions.size() * 12 + geometry.indices.size() * 8);
  for (size_t v = 0; v < geometry.vertexCount(); ++v)
    fmt::format_to(std::back_inserter(text), "v {} {} {}\n", geometry.positions[3 * v], geometry.positions[3 * v + 1],
                   geometry.positions[3 * v + 2]);
  for (size_t t = 0; t < geometry.triangleCount(); ++t)
    fmt::format_to(std::back_inserter(text), "f {} {} {}\n", geometry.indices[3 * t] + 1, geometry.indices[3 * t + 1] + 1,
                   geometry.indices[3 * t + 2] + 1);
  return text;
}

}  // namespace aor
