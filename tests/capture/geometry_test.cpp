// Format 1.1's geometry: a capture with an OBJ round-trips, version 1 captures read unchanged, and a
// bad OBJ or a bad "geometry" field is an InputError naming the file and the line (or field).
#include "capture/content_hash.h"
#include "test_support.h"

namespace aor::test {
namespace {

constexpr int kW = 8, kH = 6;

CaptureGeometry twoTriangles() {
  CaptureGeometry g;
  g.positions = {0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.1f, 1.0f / 3.0f, -2.5e-7f, 12345.678f, -1.0f, 3.0f};
  g.indices = {0, 1, 2, 2, 1, 3};
  return g;
}

class Geometry : public TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    cap = dir / "cap";
    const CaptureGeometry g = twoTriangles();
    writeCapture(cap, kW, kH, makeFrames(kW, kH, 1), {{"ao_radius", 0.5}}, &g);
  }
  void writeObj(const std::string& text) { writeBytes(cap / "scene.obj", text); }
  CaptureGeometry load() { return loadGeometry(loadCapture(cap)); }
  fs::path cap;
};

const std::string kObj = "cap/scene.obj";

TEST_F(Geometry, RoundTripsBitIdentically) {
  const nlohmann::json doc = readJson(cap / "capture.json");
  EXPECT_EQ(doc["version"].get<double>(), 1.1);
  EXPECT_EQ(doc["geometry"], "scene.obj");
  const Capture c = loadCapture(cap);
  ASSERT_TRUE(c.geometry);
  const CaptureGeometry g = loadGeometry(c), wrote = twoTriangles();
  ASSERT_EQ(g.positions.size(), wrote.positions.size());
  for (size_t i = 0; i < g.positions.size(); ++i) EXPECT_TRUE(sameBits(g.positions[i], wrote.positions[i])) << i;
  EXPECT_EQ(g.indices, wrote.indices);
  const auto files = captureFiles(c);
  EXPECT_NE(std::find(files.begin(), files.end(), c.geometry), files.end()) << "outputs must not overwrite the OBJ";
}

TEST_F(Geometry, IsPartOfTheContentHash) {
  const std::string before = captureContentSha256(loadCapture(cap));
  writeObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_NE(captureContentSha256(loadCapture(cap)), before) << "an edited OBJ is another capture";
}

TEST_F(Geometry, VersionOneCapturesHaveNone) {
  writeCapture(cap, kW, kH, makeFrames(kW, kH, 1), {});
  const nlohmann::json doc = readJson(cap / "capture.json");
  EXPECT_TRUE(doc["version"].is_number_integer());
  EXPECT_FALSE(doc.contains("geometry"));
  const Capture c = loadCapture(cap);
  EXPECT_FALSE(c.geometry);
  EXPECT_INPUT_ERROR(loadGeometry(c), "cap/capture.json", "field \"geometry\"", "has no geometry");
}

TEST_F(Geometry, PolygonsAreSplitIntoTriangles) {
  writeObj("# a quad and a triangle\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nf -1 -2 -3\n");
  const CaptureGeometry g = load();
  EXPECT_EQ(g.vertexCount(), 4u);
  EXPECT_EQ(g.triangleCount(), 3u);
}

TEST_F(Geometry, FieldNeedsVersionOnePointOne) {
  nlohmann::json doc = readJson(cap / "capture.json");
  doc["version"] = 1;
  writeJson(cap / "capture.json", doc);
  EXPECT_INPUT_ERROR(loadCapture(cap), "cap/capture.json", "field \"geometry\"", "1.1");
}

TEST_F(Geometry, PathRulesApply) {
  nlohmann::json doc = readJson(cap / "capture.json");
  doc["geometry"] = "../scene.obj";
  writeJson(cap / "capture.json", doc);
  EXPECT_INPUT_ERROR(loadCapture(cap), "field \"geometry\"", "leaves the capture folder");
  doc["geometry"] = "missing.obj";
  writeJson(cap / "capture.json", doc);
  EXPECT_INPUT_ERROR(loadCapture(cap), "field \"geometry\"", "missing.obj");
  doc["geometry"] = 3;
  writeJson(cap / "capture.json", doc);
  EXPECT_INPUT_ERROR(loadCapture(cap), "field \"geometry\"", "expected a string");
}

TEST_F(Geometry, NonFiniteCoordinateNamesItsLine) {
  writeObj("v 0 0 0\nv 1 0 0\n\nv 0 nan 0\nf 1 2 3\n");
  EXPECT_INPUT_ERROR(load(), kObj, "line 4", "coordinate y", "not a finite 32-bit float");
  writeObj("v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_INPUT_ERROR(load(), kObj, "line 2", "coordinate x");
  writeObj("v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_INPUT_ERROR(load(), kObj, "line 2", "coordinate z", "missing");
}

TEST_F(Geometry, IndexOutOfRangeNamesItsLine) {
  writeObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n# end\n");
  EXPECT_INPUT_ERROR(load(), kObj, "line 5", "face index 4 is past the last vertex", "3 vertices");
  writeObj("v 0 0 0\nv 1 0 0\nf -1 -2 -3\nv 0 1 0\n");
  EXPECT_INPUT_ERROR(load(), kObj, "line 3", "face index -3 reaches before the first vertex");
  writeObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
  EXPECT_INPUT_ERROR(load(), kObj, "line 4", "index 0");
  writeObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n");
  EXPECT_INPUT_ERROR(load(), kObj, "line 4", "at least 3 vertices");
}

TEST_F(Geometry, ForwardReferencesAreLegal) {
  writeObj("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n");
  EXPECT_EQ(load().triangleCount(), 1u);
}

TEST_F(Geometry, FileWithoutTrianglesIsRefused) {
  writeObj("v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  EXPECT_INPUT_ERROR(load(), kObj, "line 3", "no triangle");
}

}  // namespace
}  // namespace aor::test
