// The scene geometry every generated capture carries (format 1.1's scene.obj): what RayScene
// traces, as triangles, written and read back unchanged, and the analytic primitives' tessellation
// on their exact surfaces.
#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>
#include <unistd.h>

#include "capture/capture.h"
#include "generator/generator_internal.h"

using namespace aor::gen;
namespace fs = std::filesystem;

namespace {

glm::dvec3 vertex(const aor::CaptureGeometry& g, size_t v) {
  return {g.positions[3 * v], g.positions[3 * v + 1], g.positions[3 * v + 2]};
}

TEST(SceneGeometry, EveryScenesTrianglesAreFiniteAndIncludeTheFloor) {
  for (const auto& name : sceneNames()) {
    const RayScene scene(name);
    const aor::CaptureGeometry g = scene.triangles();
    ASSERT_GT(g.triangleCount(), scene.triangleCount()) << name << ": the meshes and the tessellated primitives";
    double lowest = 1e30, widest = 0;
    for (size_t v = 0; v < g.vertexCount(); ++v) {
      glm::dvec3 p = vertex(g, v);
      ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) << name;
      lowest = std::min(lowest, p.y);
      widest = std::max(widest, std::abs(p.x));
    }
    for (uint32_t i : g.indices) ASSERT_LT(i, g.vertexCount()) << name;
    EXPECT_EQ(widest, 5000.0) << name << ": the floor's 1e4 m square";
    EXPECT_EQ(lowest, name == "pit" ? -1.0 : 0.0) << name;
  }
}

TEST(SceneGeometry, TessellatedPrimitivesLieOnTheirSurfaces) {
  const aor::CaptureGeometry sphere = RayScene("sphere").triangles();
  int onSphere = 0;
  for (size_t v = 0; v < sphere.vertexCount(); ++v) {
    glm::dvec3 p = vertex(sphere, v);
    if (p.y == 0.0 && std::abs(p.x) == 5000.0) continue;  // the floor's corners
    EXPECT_NEAR(glm::length(p - glm::dvec3(0, 1, 0)), 1.0, 1e-6);
    ++onSphere;
  }
  EXPECT_GT(onSphere, 1000);
  const aor::CaptureGeometry pit = RayScene("pit").triangles();
  for (size_t v = 0; v < pit.vertexCount(); ++v) {
    glm::dvec3 p = vertex(pit, v);
    double r = std::hypot(p.x, p.z), square = std::max(std::abs(p.x), std::abs(p.z));
    bool rim = std::abs(r - 1.0) < 1e-6, outer = std::abs(square - 5000.0) < 1e-3, centre = r == 0.0 && p.y == -1.0;
    EXPECT_TRUE(rim || outer || centre) << p.x << " " << p.y << " " << p.z;
  }
}

TEST(SceneGeometry, GeneratedCapturesCarryItBitIdentically) {
  const fs::path out = fs::path(testing::TempDir()) / ("aor_generator_geometry_" + std::to_string(::getpid()));
  fs::remove_all(out);
  GeneratorOptions o;
  o.scene = "thin";
  o.path = "static";
  o.width = 16;
  o.height = 9;
  o.frames = 1;
  generateCapture(o, out);
  const aor::Capture capture = aor::loadCapture(out);
  ASSERT_TRUE(capture.geometry);
  const aor::CaptureGeometry read = aor::loadGeometry(capture), traced = RayScene("thin").triangles();
  EXPECT_EQ(read.indices, traced.indices);
  ASSERT_EQ(read.positions.size(), traced.positions.size());
  for (size_t i = 0; i < read.positions.size(); ++i) ASSERT_EQ(read.positions[i], traced.positions[i]) << i;
  fs::remove_all(out);
}

}  // namespace
