// The self-check's arithmetic without RenderDoc: one tilted triangle in front of the camera, its
// clip-space corners as a vertex shader would output them, and a depth image made independently
// (a ray per pixel centre through the capture's own camera, hitting the triangle's plane). A
// correct frame passes, in Vulkan's and in OpenGL's conventions; each mistake fails the test the
// self-check means for it.
#include <algorithm>
#include <array>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "import/self_check.h"

namespace aor {
namespace {

constexpr int kWidth = 64, kHeight = 36;
using Triangle = std::array<glm::vec3, 3>;  // view space
const Triangle kTriangle = {glm::vec3(-3.0f, -2.0f, -4.0f), glm::vec3(2.5f, -1.5f, -7.0f), glm::vec3(0.5f, 2.5f, -5.0f)};

// Vulkan's projection as the capture format wants it: [0, 1] depth, NDC y down.
glm::mat4 captureProjection() {
  glm::mat4 p = glm::perspectiveRH_ZO(glm::radians(60.0f), float(kWidth) / float(kHeight), 0.1f, 40.0f);
  p[1][1] = -p[1][1];
  return p;
}

// The capture's depth, by a ray per pixel centre (captures/FORMAT.md's reconstruction run
// backwards) against the triangle's plane; far (1) where the ray misses the triangle.
std::vector<float> rayTracedDepth(const glm::mat4& p, const Triangle& triangle) {
  const glm::dvec3 a(triangle[0]), b(triangle[1]), c(triangle[2]);
  const glm::dvec3 n = glm::cross(b - a, c - a);
  std::vector<float> depth(size_t(kWidth * kHeight), 1.0f);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const double nx = (2.0 * x + 1.0) / kWidth - 1.0, ny = (2.0 * y + 1.0) / kHeight - 1.0;
      const glm::dvec3 dir((nx + p[2][0]) / p[0][0], (ny + p[2][1]) / p[1][1], -1.0);  // at distance 1
      const double t = glm::dot(n, a) / glm::dot(n, dir);
      const glm::dvec3 hit = t * dir;
      const bool inside = t > 0.0 && glm::dot(glm::cross(b - a, hit - a), n) >= 0 && glm::dot(glm::cross(c - b, hit - b), n) >= 0 &&
                          glm::dot(glm::cross(a - c, hit - c), n) >= 0;
      if (inside) depth[size_t(y * kWidth + x)] = float((p[2][2] * -t + p[3][2]) / t);
    }
  return depth;
}

struct Frame {
  std::vector<float> depth;
  SelfCheckInput input;
};

// A Vulkan frame: the application's projection is the capture's.
Frame vulkanFrame(const Triangle& triangle = kTriangle) {
  Frame f;
  f.depth = rayTracedDepth(captureProjection(), triangle);
  SelfCheckInput& in = f.input;
  in.conventions.api = "Vulkan";
  in.viewport = {0, 0, float(kWidth), float(kHeight)};
  in.rect = {0, 0, kWidth, kHeight, false};
  in.appProjection = in.captureProjection = captureProjection();
  for (const glm::vec3& v : triangle) in.corners.push_back(in.appProjection * glm::vec4(v, 1.0f));
  in.depthQuantum = 0.0;
  return f;
}

// The same picture from an OpenGL program: clip z in [-1, 1], y up, rows stored bottom-up; the
// capture holds the import's converted projection.
Frame glFrame() {
  Frame f = vulkanFrame();
  SelfCheckInput& in = f.input;
  in.conventions = {"OpenGL", true, false, true};
  in.appProjection = glm::perspectiveRH_NO(glm::radians(60.0f), float(kWidth) / float(kHeight), 0.1f, 40.0f);
  glm::mat4 converted = projectionToWindowDepth(in.conventions, in.appProjection);
  for (int col = 0; col < 4; ++col) converted[col][1] = -converted[col][1];
  in.captureProjection = converted;
  in.corners.clear();
  for (const glm::vec3& v : kTriangle) in.corners.push_back(in.appProjection * glm::vec4(v, 1.0f));
  return f;
}

SelfCheckResult check(Frame& f) {
  f.input.depth = &f.depth;
  return runSelfCheck(f.input);
}

void expectPasses(const SelfCheckResult& r) {
  EXPECT_TRUE(r.depthRowPassed()) << r.depthRowResidual;
  EXPECT_TRUE(r.depthPassed()) << r.matched << " matched, " << r.disagreed << " disagreed";
  EXPECT_GE(r.matched, kSelfCheckMinPoints);
  EXPECT_EQ(r.disagreed, 0u);
  EXPECT_EQ(r.verticesOnScreen, 3u);
}

TEST(SelfCheckArithmetic, VulkanFrameMatchesTheRayTracedDepth) {
  Frame f = vulkanFrame();
  expectPasses(check(f));
}

TEST(SelfCheckArithmetic, OpenGLFrameOfTheSamePictureMatchesToo) {
  Frame f = glFrame();
  const SelfCheckResult r = check(f);
  expectPasses(r);
  EXPECT_NEAR(f.input.captureProjection[2][2], captureProjection()[2][2], 1e-6);  // the conversion is Vulkan's
}

TEST(SelfCheckArithmetic, RowsUpsideDownDisagree) {
  Frame f = vulkanFrame();
  for (int y = 0; y < kHeight / 2; ++y)
    std::swap_ranges(f.depth.begin() + y * kWidth, f.depth.begin() + (y + 1) * kWidth,
                     f.depth.begin() + (kHeight - 1 - y) * kWidth);
  const SelfCheckResult r = check(f);
  EXPECT_TRUE(r.depthRowPassed());
  EXPECT_FALSE(r.depthPassed()) << r.matched << " matched, " << r.disagreed << " disagreed";
}

TEST(SelfCheckArithmetic, GlDepthKeptInItsOwnRangeDisagrees) {
  Frame f = glFrame();
  f.input.captureProjection = f.input.appProjection;  // clip z [-1, 1] taken as [0, 1]
  f.input.captureProjection[1][1] = -f.input.captureProjection[1][1];
  EXPECT_FALSE(check(f).depthPassed());
}

TEST(SelfCheckArithmetic, AnotherProjectionFailsTheDepthRow) {
  Frame f = vulkanFrame();
  f.input.appProjection = glm::perspectiveRH_ZO(glm::radians(60.0f), float(kWidth) / float(kHeight), 0.5f, 20.0f);
  const SelfCheckResult r = check(f);
  EXPECT_FALSE(r.depthRowPassed());
  EXPECT_GT(r.depthRowResidual, 1e-2);
}

TEST(SelfCheckArithmetic, NearerSurfacesHideWithoutDisagreeing) {
  Frame f = vulkanFrame();
  for (int y = 0; y < kHeight; ++y)  // a nearer object over the left third of the picture
    for (int x = 0; x < kWidth / 3; ++x) f.depth[size_t(y * kWidth + x)] = 0.5f;
  const SelfCheckResult r = check(f);
  EXPECT_GT(r.hidden, 0u);
  EXPECT_EQ(r.disagreed, 0u);
  EXPECT_TRUE(r.depthPassed()) << r.matched << " matched, " << r.hidden << " hidden of " << r.points;
}

TEST(SelfCheckArithmetic, ATriangleThroughTheEyePlaneIsCheckedOnItsVisiblePart) {
  // The first corner moved behind the camera, along its edge from the second.
  Triangle through = kTriangle;
  through[0] = kTriangle[1] + 3.0f * (kTriangle[0] - kTriangle[1]);
  ASSERT_GT(through[0].z, 0.0f);
  Frame f = vulkanFrame(through);
  ASSERT_LT(f.input.corners[0].w, 0.0f);
  const SelfCheckResult r = check(f);
  EXPECT_GE(r.matched, kSelfCheckMinPoints);
  EXPECT_EQ(r.disagreed, 0u);
}

// The standard sample locations a multisampled import is checked at: the 4x table as the Vulkan
// specification lists it, every location distinct and inside its pixel, none for other counts.
TEST(SelfCheck, StandardSamplePositions) {
  const glm::dvec2 four[] = {{0.375, 0.125}, {0.875, 0.375}, {0.125, 0.625}, {0.625, 0.875}};
  for (int s = 0; s < 4; ++s) EXPECT_EQ(*standardSamplePosition(4, s), four[s]);
  EXPECT_EQ(*standardSamplePosition(1, 0), glm::dvec2(0.5, 0.5));
  for (int count : {2, 8, 16}) {
    std::vector<glm::dvec2> seen;
    for (int s = 0; s < count; ++s) {
      const auto p = standardSamplePosition(count, s);
      ASSERT_TRUE(p.has_value());
      EXPECT_TRUE(p->x >= 0.0 && p->x < 1.0 && p->y >= 0.0 && p->y < 1.0);
      EXPECT_EQ(std::count(seen.begin(), seen.end(), *p), 0);
      seen.push_back(*p);
    }
  }
  EXPECT_FALSE(standardSamplePosition(3, 0).has_value());
  EXPECT_FALSE(standardSamplePosition(4, 4).has_value());
}

}  // namespace
}  // namespace aor
