// captures/FORMAT.md stays true: its example loads, and its depth formulas invert the projections
// it allows.
#include <glm/gtc/matrix_transform.hpp>

#include "test_support.h"

namespace aor::test {
namespace {

using FormatDoc = TempDirTest;

TEST_F(FormatDoc, MinimalExampleLoads) {
  const std::string doc = readBytes(fs::path(AOR_SOURCE_DIR) / "captures/FORMAT.md");
  const auto begin = doc.find("```json\n");
  ASSERT_NE(begin, std::string::npos) << "no ```json block in FORMAT.md";
  const auto end = doc.find("```", begin + 8);
  ASSERT_NE(end, std::string::npos);
  const fs::path cap = dir / "example";
  fs::create_directories(cap / "frames");
  writeBytes(cap / "capture.json", doc.substr(begin + 8, end - begin - 8));
  writeExrWithChannels(cap / "frames/0000.exr", 8, 6, {{"depth", ExrPixelType::Float}});
  const Capture c = loadCapture(cap);
  ASSERT_EQ(c.frames.size(), 1u);
  EXPECT_EQ(c.width, 8);
  EXPECT_EQ(c.height, 6);
  // It is the projection the text describes (60 degrees, 8/6, near 0.1, far 100), to 6 digits.
  const glm::mat4 p = glm::perspective(glm::radians(60.0f), 8.0f / 6.0f, 0.1f, 100.0f);
  for (int k = 0; k < 16; ++k) EXPECT_NEAR(c.frames[0].projection[k / 4][k % 4], p[k / 4][k % 4], 1e-6f) << k;
}

// d = (P22 z + P32) / -z ; dist = P32 / (d + P22) ; X = dist (ndc.x + P20) / P00 ; reversed iff P32 > 0.
TEST(FormatDocFormulas, DepthAndPositionReconstruction) {
  struct Case {
    const char* name;
    glm::mat4 p;
    bool reversed;
    double far;  // distance of the far plane; 0 for an infinite one
  };
  glm::mat4 jittered = glm::perspective(glm::radians(50.0f), 1.5f, 0.2f, 80.0f);
  jittered[2][0] = 0.003f;
  jittered[2][1] = -0.002f;
  jittered[1][1] = -jittered[1][1];  // Vulkan y flip
  const Case cases[] = {
      {"standard finite", glm::perspective(glm::radians(60.0f), 1.5f, 0.1f, 100.0f), false, 100.0},
      {"standard infinite", glm::infinitePerspectiveRH(glm::radians(60.0f), 1.5f, 0.1f), false, 0.0},
      {"reversed finite", glm::perspective(glm::radians(60.0f), 1.5f, 100.0f, 0.1f), true, 100.0},
      {"reversed infinite", makeReversedInfiniteProjection(12, 8), true, 0.0},
      {"jittered, y flipped", jittered, false, 80.0},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    EXPECT_EQ(c.p[3][2] > 0.0f, c.reversed);
    const glm::dvec4 view(1.3, -0.7, -7.5, 1.0);
    const glm::dvec4 clip = glm::dmat4(c.p) * view;
    const double d = clip.z / clip.w;
    EXPECT_NEAR(d, (c.p[2][2] * view.z + c.p[3][2]) / -view.z, 1e-12);
    const glm::dvec2 ndc(clip.x / clip.w, clip.y / clip.w);
    const double dist = c.p[3][2] / (d + c.p[2][2]);
    EXPECT_NEAR(dist, 7.5, 1e-9);
    EXPECT_NEAR(dist * (ndc.x + c.p[2][0]) / c.p[0][0], view.x, 1e-9);
    EXPECT_NEAR(dist * (ndc.y + c.p[2][1]) / c.p[1][1], view.y, 1e-9);
    // Far value: 1 standard, 0 reversed (the limit for infinite far planes).
    const glm::dvec4 far = glm::dmat4(c.p) * glm::dvec4(0.0, 0.0, c.far > 0 ? -c.far : -1e12, 1.0);
    EXPECT_NEAR(far.z / far.w, c.reversed ? 0.0 : 1.0, 1e-6);
  }
}

}  // namespace
}  // namespace aor::test
