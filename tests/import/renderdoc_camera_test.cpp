// The import's camera checks and conventions: RenderDoc's row order, combined matrices refused
// with a message that says what is missing, exact handedness and viewport flips, cropping.
#include <functional>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "import/import_problem.h"
#include "import/api_conventions.h"
#include "import/renderdoc_camera.h"

namespace aor {
namespace {

glm::mat4 vulkanPerspective() {
  glm::mat4 p = glm::perspectiveRH_ZO(glm::radians(60.0f), 16.0f / 9.0f, 0.1f, 40.0f);
  p[1][1] = -p[1][1];
  return p;
}

std::string problemOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const ImportProblem& e) {
    return e.field + ": " + e.what();
  }
  return "no problem";
}

TEST(RenderDocCamera, RowsBecomeGlmColumns) {
  std::array<float, 16> rows{};
  for (int i = 0; i < 16; ++i) rows[size_t(i)] = float(i);
  const glm::mat4 m = matrixFromRows(rows);
  EXPECT_EQ(m[3][0], 3.0f) << "row 0, column 3 (a translation) is rows[3]";
  EXPECT_EQ(m[0][3], 12.0f);
}

TEST(RenderDocCamera, CombinedMatrixNamedAsOneOfTheTwoIsRefusedPointingToViewProjection) {
  const glm::mat4 view = glm::lookAt(glm::vec3(3, 2, 4), glm::vec3(0), glm::vec3(0, 1, 0));
  const glm::mat4 mvp = vulkanPerspective() * view;
  const std::string asProjection = problemOf([&] { checkProjectionMatrix(mvp, "ubuf.MVP"); });
  EXPECT_NE(asProjection.find("--projection: ubuf.MVP is not a perspective projection: its last row is"),
            std::string::npos) << asProjection;
  EXPECT_NE(asProjection.find("as separate members, or a combined view-projection matrix as --view-projection"),
            std::string::npos) << asProjection;
  const std::string asView = problemOf([&] { checkViewMatrix(mvp, "ubuf.MVP"); });
  EXPECT_NE(asView.find("--view: ubuf.MVP is not a world -> view transform"), std::string::npos) << asView;
  EXPECT_EQ(problemOf([&] { checkViewMatrix(view, "c.view"); }), "no problem");
  EXPECT_EQ(problemOf([&] { checkProjectionMatrix(vulkanPerspective(), "c.projection"); }), "no problem");
}

TEST(RenderDocCamera, OrthographicAndSingularProjectionsAreRefused) {
  const glm::mat4 ortho = glm::orthoRH_ZO(-1.0f, 1.0f, -1.0f, 1.0f, 0.1f, 10.0f);
  EXPECT_NE(problemOf([&] { checkProjectionMatrix(ortho, "c.p"); }).find("(0, 0, 0, 1), an orthographic"),
            std::string::npos);
  glm::mat4 singular = vulkanPerspective();
  singular[3][2] = 0.0f;
  EXPECT_NE(problemOf([&] { checkProjectionMatrix(singular, "c.p"); }).find("singular"), std::string::npos);
}

TEST(RenderDocCamera, LeftHandedAndFlippedViewportGiveTheSameClipSpace) {
  const glm::mat4 lhView = glm::lookAtLH(glm::vec3(3, 2, 4), glm::vec3(0), glm::vec3(0, 1, 0));
  const glm::mat4 lhProjection = glm::perspectiveLH_ZO(glm::radians(60.0f), 1.5f, 0.1f, 40.0f);
  checkProjectionMatrix(lhProjection, "c.p");
  const ImportedCamera c = importCamera(lhView, lhProjection, true);
  EXPECT_EQ(c.projection[2][3], -1.0f);
  EXPECT_EQ(c.adjustments.size(), 2u);
  const glm::vec4 world(0.3f, 0.7f, -0.2f, 1.0f);
  const glm::vec4 before = lhProjection * lhView * world, after = c.projection * c.view * world;
  EXPECT_EQ(after.x, before.x);
  EXPECT_EQ(after.y, -before.y) << "y flipped for the negative-height viewport";
  EXPECT_EQ(after.z, before.z) << "depth unchanged, bit for bit";
  EXPECT_EQ(after.w, before.w);
}

TEST(RenderDocCamera, ViewportCropsAndRefusesWhatItCannotMap) {
  const ViewportRect r = viewportRect(70, 0, 180, 180, 0, 1, 320, 180);
  EXPECT_EQ(r.x, 70);
  EXPECT_EQ(r.width, 180);
  const ViewportRect flipped = viewportRect(0, 90, 160, -90, 0, 1, 160, 90);
  EXPECT_TRUE(flipped.flipsY);
  EXPECT_EQ(flipped.y, 0);
  EXPECT_EQ(flipped.height, 90);
  EXPECT_THROW(viewportRect(0.5f, 0, 100, 100, 0, 1, 320, 180), ImportProblem);
  EXPECT_THROW(viewportRect(0, 0, 400, 100, 0, 1, 320, 180), ImportProblem);
  EXPECT_NO_THROW(viewportRect(0, 0, 320, 180, 1, 0, 320, 180)) << "a reversed range is folded into the projection";
  EXPECT_NO_THROW(viewportRect(0, 0, 320, 180, 0.1f, 1, 320, 180));
  EXPECT_NE(problemOf([] { viewportRect(0, 0, 320, 180, 0.5f, 0.5f, 320, 180); }).find("maps depth to [0.5, 0.5]: every "
                                                                                        "depth it stores is one value"),
            std::string::npos);
  EXPECT_THROW(viewportRect(0, 0, 320, 180, 0, 2, 320, 180), ImportProblem);
}

// Issue 45 (Warzone 2100 draws with viewport depth [0.1, 1]): the range folded into the depth row
// gives every point the window depth the draw stored, for [0, 1] and [-1, 1] clip z alike.
TEST(RenderDocCamera, AViewportDepthRangeFoldsIntoTheProjection) {
  const glm::mat4 p = vulkanPerspective();
  for (bool glClip : {false, true})
    for (const glm::dvec2 range : {glm::dvec2(0.1, 1.0), glm::dvec2(1.0, 0.0), glm::dvec2(0.25, 0.75)}) {
      ApiConventions c;
      c.clipZMinusOneToOne = glClip;
      c.depthRangeMin = range.x;
      c.depthRangeMax = range.y;
      const glm::mat4 folded = projectionToWindowDepth(c, p);
      for (float z : {-0.2f, -1.0f, -7.5f, -39.0f}) {
        const glm::vec4 clip = p * glm::vec4(0.3f, -0.2f, z, 1.0f), window = folded * glm::vec4(0.3f, -0.2f, z, 1.0f);
        EXPECT_NEAR(window.z / window.w, windowDepth(c, clip.z / clip.w), 1e-6) << z;
        EXPECT_EQ(window.w, clip.w);
      }
    }
}

TEST(RenderDocCamera, ViewSpaceNormalsGoToWorldSpace) {
  const glm::mat4 view = glm::lookAt(glm::vec3(3, 2, 4), glm::vec3(0), glm::vec3(0, 1, 0));
  const glm::vec3 worldUp(0, 1, 0);
  const glm::vec3 viewUp = glm::mat3(view) * worldUp;
  std::vector<float> normals = {viewUp.x, viewUp.y, viewUp.z, 0, 0, 0};
  viewNormalsToWorld(normals, view);
  EXPECT_NEAR(normals[0], 0.0f, 1e-6f);
  EXPECT_NEAR(normals[1], 1.0f, 1e-6f);
  EXPECT_NEAR(normals[2], 0.0f, 1e-6f);
  EXPECT_EQ(normals[4], 0.0f) << "an empty texel stays empty";
}

TEST(RenderDocCamera, DescribesTheProjection) {
  EXPECT_EQ(describeProjection(vulkanPerspective()),
            "perspective, standard depth, near 0.1, far 40, vertical field of view 60.0 degrees");
}

// A viewport depth range folded into the projection (Warzone 2100's [0.1, 1], reversed [1, 0])
// leaves the camera's near and far planes where they were (they read 0.067 and -0.2 before).
TEST(RenderDocCamera, DescribesTheCameraNotTheFoldedRange) {
  for (const auto& [a, b] : {std::pair{0.25, 0.75}, std::pair{0.1, 1.0}, std::pair{1.0, 0.0}, std::pair{0.9, 0.1}}) {
    ApiConventions c;
    c.depthRangeMin = a;
    c.depthRangeMax = b;
    const std::string reversed = a > b ? "reversed" : "standard";
    EXPECT_EQ(describeProjection(projectionToWindowDepth(c, vulkanPerspective()), a, b),
              "perspective, " + reversed + " depth, near 0.1, far 40, vertical field of view 60.0 degrees")
        << a << ", " << b;
  }
}

}  // namespace
}  // namespace aor
