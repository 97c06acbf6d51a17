// Primary visibility: depth/normal conventions, pixel orientation, thread independence, paths.
#include <cmath>
#include <map>
#include <memory>

#include <gtest/gtest.h>
#include <glm/matrix.hpp>

#include "generator/generator_internal.h"

using namespace aor::gen;
using glm::dvec3;
using glm::dvec4;

namespace {

constexpr double kPi = 3.14159265358979323846;

const RayScene& scene(const std::string& name) {
  static std::map<std::string, std::unique_ptr<RayScene>> cache;
  auto& s = cache[name];
  if (!s) s = std::make_unique<RayScene>(name);
  return *s;
}

double expectedDepth(double d, bool reversed, bool infinite) {
  const double n = kNearPlane, f = kFarPlane;
  if (!reversed) return infinite ? 1.0 - n / d : f / (f - n) * (1.0 - n / d);
  return infinite ? n / d : n * (f - d) / (d * (f - n));
}

// World position from pixel centre + stored depth, the way a replay reconstructs it.
dvec3 reconstruct(const FrameCamera& cam, int x, int y, int w, int h, float depth) {
  const glm::dmat4 inv = glm::inverse(glm::dmat4(cam.projection) * glm::dmat4(cam.view));
  const dvec4 p = inv * dvec4((2.0 * x + 1.0) / w - 1.0, (2.0 * y + 1.0) / h - 1.0, depth, 1.0);
  return dvec3(p) / p.w;
}

struct Variant {
  bool reversed, infinite;
};
const Variant kVariants[] = {{false, false}, {false, true}, {true, false}, {true, true}};

}  // namespace

TEST(Projection, MapsViewDepthAndFlipsY) {
  for (const auto v : kVariants) {
    const glm::dmat4 P(makeProjection(60.0, 16.0 / 9.0, v.reversed, v.infinite));
    for (double d : {0.05, 1.0, 7.5, 150.0}) {
      const dvec4 c = P * dvec4(0.0, 0.0, -d, 1.0);
      EXPECT_NEAR(c.z / c.w, expectedDepth(d, v.reversed, v.infinite), 1e-6) << d;
    }
    const dvec4 up = P * dvec4(0.0, 1.0, -5.0, 1.0);
    EXPECT_LT(up.y / up.w, 0.0) << "view +Y must map to NDC -y (top row)";
    const dvec4 right = P * dvec4(1.0, 0.0, -5.0, 1.0);
    EXPECT_GT(right.x / right.w, 0.0);
  }
  // Standard finite is glm::perspectiveRH_ZO with P[1][1] negated.
  const glm::mat4 P = makeProjection(60.0, 2.0, false, false);
  const double t = std::tan(30.0 * kPi / 180.0);
  EXPECT_FLOAT_EQ(P[1][1], static_cast<float>(-1.0 / t));
  EXPECT_FLOAT_EQ(P[0][0], static_cast<float>(1.0 / (2.0 * t)));
  EXPECT_FLOAT_EQ(P[2][3], -1.0f);
}

TEST(GBuffer, StraightDownAtThePlaneGivesPredictedDepthAndUpNormal) {
  for (const auto v : kVariants) {
    for (double h : {0.5, 3.0, 40.0}) {
      FrameCamera cam;
      cam.view = makeView({0.0, h, 0.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, -1.0});
      cam.projection = makeProjection(60.0, 64.0 / 36.0, v.reversed, v.infinite);
      RenderSettings rs;
      rs.width = 64;
      rs.height = 36;
      rs.reversedZ = v.reversed;
      const auto frame = renderFrame(scene("plane"), cam, rs, 0);
      const double expected = expectedDepth(h, v.reversed, v.infinite);
      // Every pixel sees the plane at view depth h; check the image centre and all others.
      for (size_t i = 0; i < frame.gbuffer.depth.size(); ++i) {
        ASSERT_NEAR(frame.gbuffer.depth[i], expected, 2e-6 * std::max(1.0, expected))
            << "h=" << h << " reversed=" << v.reversed << " infinite=" << v.infinite << " pixel " << i;
        ASSERT_EQ(frame.gbuffer.normals[3 * i + 0], 0.0f);
        ASSERT_EQ(frame.gbuffer.normals[3 * i + 1], 1.0f);
        ASSERT_EQ(frame.gbuffer.normals[3 * i + 2], 0.0f);
      }
      EXPECT_FALSE(frame.reference.has_value());
    }
  }
}

TEST(GBuffer, SkyIsExactlyTheFarValueAndTopRowIsUp) {
  for (const auto v : kVariants) {
    FrameCamera cam;
    cam.view = makeView({0.0, 1.0, 0.0}, {0.0, 1.0, -10.0});  // horizontal view
    cam.projection = makeProjection(60.0, 64.0 / 36.0, v.reversed, v.infinite);
    RenderSettings rs;
    rs.width = 64;
    rs.height = 36;
    rs.reversedZ = v.reversed;
    rs.referenceSpp = 4;
    const auto frame = renderFrame(scene("plane"), cam, rs, 0);
    const float sky = v.reversed ? 0.0f : 1.0f;
    for (int x = 0; x < 64; ++x) {
      // Row 0 is the top of the image: above the horizon.
      EXPECT_EQ(frame.gbuffer.depth[x], sky);
      EXPECT_EQ(frame.gbuffer.normals[3 * x + 1], 0.0f);
      EXPECT_EQ((*frame.reference)[x], 1.0f);
      // Last row looks down at the floor.
      const size_t b = 35 * 64 + x;
      EXPECT_NE(frame.gbuffer.depth[b], sky);
      EXPECT_EQ(frame.gbuffer.normals[3 * b + 1], 1.0f);
    }
  }
}

TEST(GBuffer, FarPlaneClipsDistantGeometryToSky) {
  // Looking 1 degree below the horizon from 1 m: the floor is hit ~57 m away at the centre and far
  // beyond 200 m near the horizon. Finite far: those pixels are sky; infinite far: they are not.
  const double pitch = 1.0 * kPi / 180.0;
  FrameCamera cam;
  cam.view = makeView({0.0, 1.0, 0.0}, {0.0, 1.0 - std::sin(pitch), -std::cos(pitch)});
  int skyFinite = 0, skyInfinite = 0;
  for (bool infinite : {false, true}) {
    cam.projection = makeProjection(20.0, 2.0, false, infinite);
    RenderSettings rs;
    rs.width = 32;
    rs.height = 32;
    const auto frame = renderFrame(scene("plane"), cam, rs, 0);
    int& sky = infinite ? skyInfinite : skyFinite;
    for (float d : frame.gbuffer.depth) sky += d == 1.0f;
    for (float d : frame.gbuffer.depth) EXPECT_LE(d, 1.0f);
  }
  EXPECT_GT(skyFinite, skyInfinite);
}

// Depth + pixel centre reconstruct to points on the actual surfaces with matching normals: checks
// the whole pixel/NDC/depth contract (orientation of x and y included) for a rolled, off-axis view.
TEST(GBuffer, ReconstructedPositionsLieOnTheSurfaces) {
  for (const auto v : kVariants) {
    FrameCamera cam;
    cam.view = makeView({2.5, 1.7, 3.1}, {-0.4, 0.6, 0.2}, glm::normalize(dvec3(0.2, 1.0, 0.0)));
    cam.projection = makeProjection(50.0, 48.0 / 30.0, v.reversed, v.infinite);
    RenderSettings rs;
    rs.width = 48;
    rs.height = 30;
    rs.reversedZ = v.reversed;
    const auto frame = renderFrame(scene("sphere"), cam, rs, 0);
    int onSphere = 0, onFloor = 0;
    for (int y = 0; y < 30; ++y) {
      for (int x = 0; x < 48; ++x) {
        const size_t i = static_cast<size_t>(y) * 48 + x;
        const float depth = frame.gbuffer.depth[i];
        if (depth == (v.reversed ? 0.0f : 1.0f)) continue;
        const dvec3 p = reconstruct(cam, x, y, 48, 30, depth);
        const dvec3 n(frame.gbuffer.normals[3 * i], frame.gbuffer.normals[3 * i + 1], frame.gbuffer.normals[3 * i + 2]);
        const double tol = 2e-3 * std::max(1.0, glm::length(p - dvec3(2.5, 1.7, 3.1)));
        if (std::abs(p.y) < tol && n.y > 0.999) {
          ++onFloor;
        } else {
          const dvec3 c(0.0, 1.0, 0.0);
          ASSERT_NEAR(glm::length(p - c), 1.0, tol) << "pixel " << x << "," << y;
          ASSERT_NEAR(glm::dot(n, glm::normalize(p - c)), 1.0, 1e-3);
          ++onSphere;
        }
        ASSERT_NEAR(glm::length(n), 1.0, 1e-5);
      }
    }
    EXPECT_GT(onSphere, 100);
    EXPECT_GT(onFloor, 100);
  }
}

TEST(GBuffer, NormalsFaceTheCamera) {
  // From inside the pit looking at the wall: the wall normal must point inwards (towards the eye).
  FrameCamera cam;
  cam.view = makeView({-0.5, -0.5, 0.0}, {1.0, -0.5, 0.0});
  cam.projection = makeProjection(40.0, 1.0, false, false);
  RenderSettings rs;
  rs.width = 9;
  rs.height = 9;
  const auto frame = renderFrame(scene("pit"), cam, rs, 0);
  const size_t c = 4 * 9 + 4;
  EXPECT_NEAR(frame.gbuffer.normals[3 * c + 0], -1.0f, 1e-6);
  EXPECT_NEAR(frame.gbuffer.depth[c], expectedDepth(1.5, false, false), 1e-6);
  // Boxes: every visible normal has a non-positive dot with the view direction.
  FrameCamera cam2;
  cam2.view = makeView({9.0, 3.0, 11.0}, {0.0, 0.5, 0.0});
  cam2.projection = makeProjection(60.0, 2.0, false, false);
  rs.width = 40;
  rs.height = 20;
  const auto f2 = renderFrame(scene("boxes"), cam2, rs, 0);
  for (int y = 0; y < 20; ++y) {
    for (int x = 0; x < 40; ++x) {
      const size_t i = static_cast<size_t>(y) * 40 + x;
      if (f2.gbuffer.depth[i] == 1.0f) continue;
      const PixelRay ray = pixelRay(cam2.view, cam2.projection, false, x, y, 40, 20);
      const dvec3 n(f2.gbuffer.normals[3 * i], f2.gbuffer.normals[3 * i + 1], f2.gbuffer.normals[3 * i + 2]);
      EXPECT_LE(glm::dot(n, ray.direction), 1e-9);
    }
  }
}

TEST(GBuffer, OutputIsIndependentOfTheThreadCount) {
  const auto cams = cameraPath(scene("boxes").info(), [] {
    aor::gen::GeneratorOptions o;
    o.width = 48;
    o.height = 27;
    o.frames = 3;
    return o;
  }());
  RenderSettings rs;
  rs.width = 48;
  rs.height = 27;
  rs.referenceSpp = 8;
  rs.radius = 1.0;
  rs.threads = 1;
  const auto a = renderFrame(scene("boxes"), cams[1], rs, 1);
  rs.threads = 3;
  const auto b = renderFrame(scene("boxes"), cams[1], rs, 1);
  EXPECT_EQ(a.gbuffer.depth, b.gbuffer.depth);
  EXPECT_EQ(a.gbuffer.normals, b.gbuffer.normals);
  EXPECT_EQ(*a.reference, *b.reference);
  // Some pixels must be partially occluded, otherwise this says little.
  int partial = 0;
  for (float r : *a.reference) partial += r > 0.0f && r < 1.0f;
  EXPECT_GT(partial, 50);
  // No normals requested: none written.
  rs.writeNormals = false;
  EXPECT_TRUE(renderFrame(scene("boxes"), cams[0], rs, 0).gbuffer.normals.empty());
}

// ---- Camera paths ---------------------------------------------------------------------------

namespace {
dvec3 eyeOf(const glm::mat4& view) { return dvec3(glm::inverse(glm::dmat4(view))[3]); }
dvec3 forwardOf(const glm::mat4& view) { return -dvec3(glm::inverse(glm::dmat4(view))[2]); }
aor::gen::GeneratorOptions pathOptions(const std::string& path, int frames) {
  aor::gen::GeneratorOptions o;
  o.path = path;
  o.frames = frames;
  o.width = 32;
  o.height = 18;
  return o;
}
}  // namespace

TEST(Paths, OrbitSweepsSixtyDegreesAtConstantHeight) {
  const SceneInfo s = sceneInfo("boxes");
  const auto cams = cameraPath(s, pathOptions("orbit", 24));
  ASSERT_EQ(cams.size(), 24u);
  const dvec3 e0 = eyeOf(cams.front().view), e1 = eyeOf(cams.back().view);
  for (const auto& c : cams) {
    const dvec3 e = eyeOf(c.view);
    EXPECT_NEAR(e.y, s.height, 1e-4);
    EXPECT_NEAR(glm::length(glm::dvec2(e.x - s.focus.x, e.z - s.focus.z)), s.distance, 1e-4);
    EXPECT_FALSE(c.cut);
  }
  const glm::dvec2 a(e0.x - s.focus.x, e0.z - s.focus.z), b(e1.x - s.focus.x, e1.z - s.focus.z);
  EXPECT_NEAR(std::acos(glm::dot(a, b) / (glm::length(a) * glm::length(b))) * 180.0 / kPi, 60.0, 1e-3);
}

TEST(Paths, StaticDollyCutStrafe) {
  const SceneInfo s = sceneInfo("sphere");
  const auto st = cameraPath(s, pathOptions("static", 5));
  for (const auto& c : st) EXPECT_EQ(c.view, st[0].view);

  const auto dolly = cameraPath(s, pathOptions("dolly", 6));
  for (size_t i = 1; i < dolly.size(); ++i) {
    EXPECT_LT(glm::length(eyeOf(dolly[i].view) - s.focus), glm::length(eyeOf(dolly[i - 1].view) - s.focus));
    EXPECT_NEAR(glm::dot(forwardOf(dolly[i].view), forwardOf(dolly[0].view)), 1.0, 1e-6);
  }

  for (int n : {1, 2, 7, 24}) {
    const auto cut = cameraPath(s, pathOptions("cut", n));
    ASSERT_EQ(static_cast<int>(cut.size()), n);
    int cuts = 0;
    for (int i = 0; i < n; ++i) {
      if (cut[i].cut) {
        ++cuts;
        EXPECT_EQ(i, n / 2);
        EXPECT_GT(glm::length(eyeOf(cut[i].view) - eyeOf(cut[i - 1].view)), 1.0);
      } else if (i > 0) {
        EXPECT_LT(glm::length(eyeOf(cut[i].view) - eyeOf(cut[i - 1].view)), 0.5);
      }
    }
    EXPECT_EQ(cuts, n >= 2 ? 1 : 0);
  }

  const auto strafe = cameraPath(s, pathOptions("strafe", 9));
  const dvec3 travel = eyeOf(strafe.back().view) - eyeOf(strafe.front().view);
  EXPECT_NEAR(glm::length(travel), s.strafeSpan, 1e-4);
  for (const auto& c : strafe) {
    EXPECT_NEAR(glm::dot(forwardOf(c.view), forwardOf(strafe[0].view)), 1.0, 1e-6);
    EXPECT_NEAR(glm::dot(forwardOf(c.view), glm::normalize(travel)), 0.0, 1e-4);  // sideways
  }
}

// Every scene/path keeps the camera outside geometry and shows a fair amount of scene.
TEST(Paths, EveryFrameOfEveryScenePathSeesTheSceneFromOutside) {
  for (const auto& name : sceneNames()) {
    if (name == "bunny" && !std::filesystem::exists(defaultBunnyPath())) continue;  // glmark2-data missing
    for (const auto& path : pathNames()) {
      auto o = pathOptions(path, 24);
      o.width = 24;
      o.height = 14;
      const auto cams = cameraPath(scene(name).info(), o);
      for (size_t f = 0; f < cams.size(); ++f) {
        RenderSettings rs;
        rs.width = o.width;
        rs.height = o.height;
        const auto frame = renderFrame(scene(name), cams[f], rs, static_cast<int>(f));
        int geometry = 0, tooClose = 0;
        for (size_t i = 0; i < frame.gbuffer.depth.size(); ++i) {
          const float d = frame.gbuffer.depth[i];
          if (d == 1.0f) continue;
          ++geometry;
          tooClose += d < expectedDepth(0.25, false, false);
        }
        EXPECT_GT(geometry, static_cast<int>(frame.gbuffer.depth.size() / 5)) << name << " " << path << " " << f;
        EXPECT_EQ(tooClose, 0) << name << " " << path << " frame " << f;
      }
    }
  }
}
