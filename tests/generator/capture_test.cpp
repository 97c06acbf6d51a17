// generateCapture end to end: option checks, determinism, metadata, progress, the bunny scene.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>

#include <gtest/gtest.h>
#include <unistd.h>

#include "capture/capture.h"
#include "core/input_error.h"
#include "generator/generator_internal.h"
#include "scratch_folder.h"

using namespace aor::gen;
namespace fs = std::filesystem;

namespace {

fs::path scratch(const std::string& name) {
  const fs::path p = aor::test::processScratchFolder("aor_generator") / name;
  fs::remove_all(p);
  return p;
}

std::string readFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Relative path -> contents of every file under `folder`.
std::map<std::string, std::string> snapshot(const fs::path& folder) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(folder))
    if (e.is_regular_file()) files[fs::relative(e.path(), folder).generic_string()] = readFile(e.path());
  return files;
}

GeneratorOptions small(const std::string& scene = "boxes", const std::string& path = "cut") {
  GeneratorOptions o;
  o.scene = scene;
  o.path = path;
  o.width = 32;
  o.height = 18;
  o.frames = 4;
  o.referenceSpp = 4;
  return o;
}

template <class F>
std::string inputErrorField(F&& f) {
  try {
    f();
  } catch (const aor::InputError& e) {
    return e.field;
  } catch (const std::exception& e) {
    return std::string("wrong exception: ") + e.what();
  }
  return "no exception";
}

}  // namespace

TEST(Options, NamesAreListed) {
  const auto scenes = sceneNames();
  for (const char* s : {"plane", "pit", "sphere", "boxes", "bunny", "thin"})
    EXPECT_NE(std::find(scenes.begin(), scenes.end(), s), scenes.end()) << s;
  const auto paths = pathNames();
  for (const char* p : {"orbit", "dolly", "static", "cut", "strafe"})
    EXPECT_NE(std::find(paths.begin(), paths.end(), p), paths.end()) << p;
  EXPECT_EQ(GeneratorOptions{}.scene, "boxes");
}

TEST(Options, BadOptionsAreInputErrors) {
  const fs::path out = scratch("bad");
  auto run = [&](auto edit) {
    GeneratorOptions o = small();
    edit(o);
    return inputErrorField([&] { generateCapture(o, out); });
  };
  EXPECT_EQ(run([](GeneratorOptions& o) { o.scene = "teapot"; }), "scene");
  EXPECT_EQ(run([](GeneratorOptions& o) { o.scene = ""; }), "scene");
  EXPECT_EQ(run([](GeneratorOptions& o) { o.path = "spiral"; }), "path");
  EXPECT_EQ(run([](GeneratorOptions& o) { o.width = 0; }), "width");
  EXPECT_EQ(run([](GeneratorOptions& o) { o.width = -5; }), "width");
  EXPECT_EQ(run([](GeneratorOptions& o) { o.height = 0; }), "height");
  EXPECT_EQ(run([](GeneratorOptions& o) { o.frames = 0; }), "frames");
  EXPECT_EQ(run([](GeneratorOptions& o) { o.frames = -1; }), "frames");
  EXPECT_EQ(run([](GeneratorOptions& o) { o.referenceSpp = -1; }), "reference_spp");
  EXPECT_EQ(run([](GeneratorOptions& o) { o.radius = 0.0f; }), "radius");
  EXPECT_EQ(run([](GeneratorOptions& o) { o.radius = -1.0f; }), "radius");
  EXPECT_EQ(run([](GeneratorOptions& o) { o.verticalFovDegrees = 0.0f; }), "fov");
  EXPECT_EQ(run([](GeneratorOptions& o) { o.verticalFovDegrees = 180.0f; }), "fov");
  EXPECT_FALSE(fs::exists(out)) << "nothing may be written for bad options";
  // The message names the bad value and the valid choices.
  try {
    GeneratorOptions o = small();
    o.scene = "teapot";
    generateCapture(o, out);
    FAIL();
  } catch (const aor::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("teapot"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("boxes"), std::string::npos) << e.what();
  }
  EXPECT_EQ(inputErrorField([] { RayScene s("nope"); }), "scene");
}

TEST(Options, MissingBunnyModelNamesThePathAndThePackage) {
  const fs::path missing = "/nonexistent/aoreplay/bunny.obj";
  try {
    RayScene s("bunny", missing);
    FAIL() << "expected InputError";
  } catch (const aor::InputError& e) {
    EXPECT_EQ(e.file, missing.string());
    EXPECT_NE(std::string(e.what()).find("glmark2-data"), std::string::npos) << e.what();
  }
}

TEST(Scenes, BunnyIsAboutOneMetreTallInsideARoom) {
  if (!fs::exists(defaultBunnyPath())) GTEST_SKIP() << "glmark2-data not installed";
  const RayScene s("bunny");
  EXPECT_GT(s.triangleCount(), 60000u);
  // Highest point of the bunny, probed from above over its footprint.
  double top = 0.0;
  for (int i = 0; i <= 40; ++i)
    for (int j = 0; j <= 40; ++j) {
      const auto hit = s.intersect({-0.6 + 0.03 * i, 3.0, -0.6 + 0.03 * j}, {0, -1, 0}, 0.0, 10.0);
      ASSERT_TRUE(hit.has_value());
      top = std::max(top, hit->position.y);
    }
  EXPECT_NEAR(top, 1.0, 0.05);
  // Walls: back wall at z = -1.5 and side walls at x = +-1.8.
  EXPECT_NEAR(s.intersect({0, 1.5, 0}, {0, 0, -1}, 0.0, 10.0)->t, 1.5, 1e-6);
  EXPECT_NEAR(s.intersect({0, 1.5, 0}, {1, 0, 0}, 0.0, 10.0)->t, 1.8, 1e-6);
  EXPECT_FALSE(s.intersect({0, 1.5, 0}, {0, 0, 1}, 0.0, 100.0).has_value());  // open front
}

TEST(Scenes, BoxesHaveThinWallsAndVariedHeights) {
  const RayScene s("boxes");
  EXPECT_GT(s.triangleCount(), 500u);
  EXPECT_GT(s.meshMax().y, 3.0);
  // Probe heights from above on a grid: many distinct heights, some floor, some roofs.
  std::set<long> heights;
  int floorHits = 0;
  for (int i = 0; i < 60; ++i)
    for (int j = 0; j < 60; ++j) {
      const auto hit = s.intersect({-9.0 + 0.3 * i, 10.0, -9.0 + 0.3 * j}, {0, -1, 0}, 0.0, 20.0);
      ASSERT_TRUE(hit.has_value());
      if (hit->position.y == 0.0) ++floorHits;
      heights.insert(std::lround(hit->position.y * 100.0));
    }
  EXPECT_GT(floorHits, 300);
  EXPECT_GT(heights.size(), 20u);
  // The streets along x = 0 and z = 0 stay clear for the camera paths.
  for (double z = -9.0; z <= 9.0; z += 0.25)
    EXPECT_EQ(s.intersect({0.0, 10.0, z}, {0, -1, 0}, 0.0, 20.0)->position.y, 0.0) << z;
}

TEST(Capture, SameOptionsGiveByteIdenticalFiles) {
  const GeneratorOptions o = small("boxes", "cut");
  const fs::path a = scratch("det_a"), b = scratch("det_b");
  generateCapture(o, a);
  generateCapture(o, b);
  const auto fa = snapshot(a), fb = snapshot(b);
  ASSERT_FALSE(fa.empty());
  ASSERT_EQ(fa.size(), fb.size());
  for (const auto& [name, bytes] : fa) {
    ASSERT_TRUE(fb.count(name)) << name;
    EXPECT_TRUE(bytes == fb.at(name)) << name << " differs";
  }
  // A different seed changes the reference only.
  GeneratorOptions o2 = o;
  o2.seed = 2;
  const fs::path c = scratch("det_c");
  generateCapture(o2, c);
  const auto fc = snapshot(c);
  EXPECT_TRUE(fc.at("frames/0001.exr") == fa.at("frames/0001.exr"));
  EXPECT_FALSE(fc.at("frames/0001.ref.exr") == fa.at("frames/0001.ref.exr"));
  fs::remove_all(a);
  fs::remove_all(b);
  fs::remove_all(c);
}

TEST(Capture, MetadataFramesAndProgress) {
  GeneratorOptions o = small("sphere", "cut");
  o.frames = 5;
  o.reversedZ = true;
  o.infiniteFar = true;
  std::vector<std::pair<int, int>> calls;
  o.progress = [&](int done, int total) { calls.emplace_back(done, total); };
  const fs::path out = scratch("meta");
  generateCapture(o, out);
  ASSERT_EQ(calls.size(), 5u);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(calls[i], std::make_pair(i + 1, 5));

  const aor::Capture cap = aor::loadCapture(out);
  EXPECT_EQ(cap.width, 32);
  EXPECT_EQ(cap.height, 18);
  ASSERT_EQ(cap.frames.size(), 5u);
  EXPECT_TRUE(cap.hasNormals);
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(cap.frames[i].cut, i == 2) << i;
    EXPECT_TRUE(cap.frames[i].reference.has_value());
  }
  const auto& sc = cap.scene;
  EXPECT_EQ(sc.at("name"), "sphere");
  EXPECT_EQ(sc.at("ao_radius").get<double>(), 100.0);
  EXPECT_EQ(sc.at("units"), "meters");
  EXPECT_EQ(sc.at("path"), "cut");
  EXPECT_EQ(sc.at("reference_spp"), 4);
  EXPECT_NE(sc.at("reference").get<std::string>().find(kReferenceDescription), std::string::npos);
  EXPECT_TRUE(sc.at("generator").at("options").at("reversed_z").get<bool>());
  EXPECT_TRUE(sc.at("generator").at("far").is_null());
  EXPECT_TRUE(sc.contains("oracle"));

  // Reversed-Z sky is 0, and the frame data round-trips.
  const aor::GBuffer g = aor::loadGBuffer(cap, 0);
  int sky = 0;
  for (float d : g.depth) {
    EXPECT_GE(d, 0.0f);
    EXPECT_LE(d, 1.0f);
    sky += d == 0.0f;
  }
  EXPECT_GT(sky, 0);
  const auto ref = aor::loadReference(cap, 0);
  ASSERT_TRUE(ref.has_value());
  for (float v : *ref) {
    EXPECT_GE(v, 0.0f);
    EXPECT_LE(v, 1.0f);
  }
  fs::remove_all(out);
}

TEST(Capture, DepthOnlyWithoutReferenceAndCustomRadius) {
  GeneratorOptions o = small("thin", "strafe");
  o.writeNormals = false;
  o.referenceSpp = 0;
  o.frames = 2;
  o.radius = 0.25f;
  const fs::path out = scratch("depthonly");
  generateCapture(o, out);
  const aor::Capture cap = aor::loadCapture(out);
  EXPECT_FALSE(cap.hasNormals);
  EXPECT_FALSE(cap.frames[0].reference.has_value());
  EXPECT_EQ(cap.scene.at("ao_radius").get<double>(), 0.25);
  EXPECT_EQ(cap.scene.at("reference_spp"), 0);
  fs::remove_all(out);
}
