// The second depth layer (`--depth2`): depth peeling along each pixel's ray, with the minimum
// separation behind layer 0; deterministic; sky where nothing lies behind.
#include <cmath>
#include <memory>

#include <gtest/gtest.h>
#include <glm/matrix.hpp>

#include "core/input_error.h"
#include "generator/generator_internal.h"

using namespace aor::gen;
using glm::dvec3;
using glm::dvec4;

namespace {

const RayScene& thinScene() {
  static const auto scene = std::make_unique<RayScene>("thin");
  return *scene;
}

dvec3 worldPosition(const FrameCamera& cam, float depth) {
  // A 1x1 image: its one pixel is NDC (0, 0).
  const glm::dmat4 inv = glm::inverse(glm::dmat4(cam.projection) * glm::dmat4(cam.view));
  const dvec4 p = inv * dvec4(0.0, 0.0, depth, 1.0);
  return dvec3(p) / p.w;
}

// The thin scene's fence slat 22 spans x in [0.08, 0.16], z in [-2.01, -1.99] (2 cm thick) from the
// floor to 1.2 m, its rails at y in [0.25, 0.31] and [0.95, 1.01] behind it. A camera at
// (0.12, 1, 0.4) looks through the slat's middle at (0.12, 0.6, -2): between the pole rows, between
// the rails; beyond the slat the ray meets the floor at z = 0.4 - 2.5 * 2.4 = -5.6.
FrameCamera cameraThroughTheSlat(bool reversed) {
  FrameCamera cam;
  cam.view = makeView({0.12, 1.0, 0.4}, {0.12, 0.6, -2.0});
  cam.projection = makeProjection(30.0, 1.0, reversed, false);
  return cam;
}

aor::CaptureFrameData renderThroughTheSlat(bool reversed, double separation) {
  RenderSettings rs;
  rs.width = 1;
  rs.height = 1;
  rs.reversedZ = reversed;
  rs.depth2 = true;
  rs.depth2Separation = separation;
  return renderFrame(thinScene(), cameraThroughTheSlat(reversed), rs, 0);
}

}  // namespace

TEST(Depth2, BehindAThinSlatTheSecondLayerIsTheFloorBehindIt) {
  for (bool reversed : {false, true}) {
    // 5 cm: more than the slat's 2 cm (along this ray 2.04 cm), so its back face is skipped.
    const auto frame = renderThroughTheSlat(reversed, 0.05);
    const FrameCamera cam = cameraThroughTheSlat(reversed);
    const dvec3 first = worldPosition(cam, frame.gbuffer.depth.at(0));
    const dvec3 second = worldPosition(cam, frame.gbuffer.depth2.at(0));
    EXPECT_NEAR(first.z, -1.99, 1e-3) << "layer 0: the slat's front face";
    EXPECT_NEAR(first.y, 0.6017, 1e-3);
    EXPECT_NEAR(second.y, 0.0, 1e-3) << "layer 1: the floor";
    EXPECT_NEAR(second.z, -5.6, 1e-2);
    EXPECT_NEAR(second.x, 0.12, 1e-3);
  }
}

TEST(Depth2, TheSeparationDecidesWhetherABackFaceIsTheSecondLayer) {
  // 1 cm (the default): the slat's back face, 2 cm behind its front, is the nearest surface beyond.
  const auto frame = renderThroughTheSlat(false, 0.01);
  const FrameCamera cam = cameraThroughTheSlat(false);
  EXPECT_NEAR(worldPosition(cam, frame.gbuffer.depth2.at(0)).z, -2.01, 1e-3);
}

TEST(Depth2, NothingBehindIsSkyAndNoLayer0IsSky) {
  RenderSettings rs;
  rs.width = 16;
  rs.height = 9;
  rs.depth2 = true;
  FrameCamera cam;
  // Looking down at the bare floor (the plane scene): nothing behind any pixel.
  cam.view = makeView({0.0, 3.0, 0.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, -1.0});
  cam.projection = makeProjection(60.0, 16.0 / 9.0, false, false);
  const RayScene plane("plane");
  const auto down = renderFrame(plane, cam, rs, 0);
  for (float d : down.gbuffer.depth2) ASSERT_EQ(d, 1.0f);
  // Looking up at the sky: neither layer.
  cam.view = makeView({0.0, 3.0, 0.0}, {0.0, 10.0, 0.0}, {0.0, 0.0, -1.0});
  const auto up = renderFrame(plane, cam, rs, 0);
  for (size_t i = 0; i < up.gbuffer.depth.size(); ++i) {
    ASSERT_EQ(up.gbuffer.depth[i], 1.0f);
    ASSERT_EQ(up.gbuffer.depth2[i], 1.0f);
  }
  // Without --depth2 no second layer is written at all.
  rs.depth2 = false;
  EXPECT_TRUE(renderFrame(plane, cam, rs, 0).gbuffer.depth2.empty());
}

TEST(Depth2, IsDeterministicAndIndependentOfTheThreadCount) {
  aor::gen::GeneratorOptions o;
  o.width = 48;
  o.height = 27;
  o.frames = 2;
  o.path = "strafe";
  const auto cams = cameraPath(thinScene().info(), o);
  RenderSettings rs;
  rs.width = o.width;
  rs.height = o.height;
  rs.depth2 = true;
  rs.threads = 1;
  const auto a = renderFrame(thinScene(), cams[1], rs, 1);
  rs.threads = 3;
  const auto b = renderFrame(thinScene(), cams[1], rs, 1);
  const auto c = renderFrame(thinScene(), cams[1], rs, 1);
  EXPECT_EQ(a.gbuffer.depth2, b.gbuffer.depth2);
  EXPECT_EQ(b.gbuffer.depth2, c.gbuffer.depth2);
  EXPECT_EQ(a.gbuffer.depth, b.gbuffer.depth);
  // Layer 1 is never in front of layer 0, and some pixels have one (poles, slats over the floor).
  int behind = 0;
  for (size_t i = 0; i < a.gbuffer.depth.size(); ++i) {
    ASSERT_GE(a.gbuffer.depth2[i], a.gbuffer.depth[i]);
    behind += a.gbuffer.depth2[i] < 1.0f;
  }
  EXPECT_GT(behind, 20);
}

TEST(Depth2, TheSeparationIsChecked) {
  aor::gen::GeneratorOptions o;
  o.scene = "thin";
  o.depth2 = true;
  for (double bad : {0.0, -0.01, std::nan(""), 1e9}) {
    o.depth2Separation = bad;
    EXPECT_THROW(validateOptions(o), aor::InputError) << bad;
  }
  o.depth2Separation = 0.01;
  EXPECT_NO_THROW(validateOptions(o));
}
