// factorViewProjection (import/renderdoc_camera.h): combined matrices made from known perspective
// projections and rigid views, in the conventions programs use, split back into the same two (or,
// where the application's view is left-handed, into an equivalent right-handed pair with the same
// product); the matrices that are not a perspective projection times a rigid view are refused
// naming what was found.
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "import/import_problem.h"
#include "import/renderdoc_camera.h"

namespace aor {
namespace {

glm::mat4 rigidView(float angle, glm::vec3 axis, glm::vec3 eye) {
  return glm::rotate(glm::mat4(1.0f), angle, glm::normalize(axis)) * glm::translate(glm::mat4(1.0f), -eye);
}

double largestDifference(const glm::mat4& a, const glm::mat4& b) {
  double d = 0;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) d = std::max(d, double(std::abs(a[c][r] - b[c][r])));
  return d;
}

bool properRotation(const glm::mat4& v) {
  const glm::mat3 r(v);
  return std::abs(glm::determinant(r) - 1.0f) < 1e-5f && largestDifference(glm::mat4(glm::transpose(r) * r), glm::mat4(1.0f)) < 1e-5;
}

std::string problemOf(const glm::mat4& m) {
  try {
    factorViewProjection(m, "cb.mvp");
  } catch (const ImportProblem& e) {
    EXPECT_EQ(e.field, "--view-projection");
    return e.what();
  }
  return "";
}

TEST(ViewProjection, RightHandedProjectionsAndRigidViewsComeBackAsTheyWere) {
  glm::mat4 vulkan = glm::perspectiveRH_ZO(glm::radians(60.0f), 16.0f / 9.0f, 0.1f, 40.0f);
  vulkan[1][1] = -vulkan[1][1];  // y down
  glm::mat4 offCentre = glm::frustumRH_ZO(-0.07f, 0.05f, -0.04f, 0.03f, 0.1f, 100.0f);
  glm::mat4 reversedInfinite(0.0f);  // reversed z, infinite far: z/w = near / -z_view
  reversedInfinite[0][0] = 1.2f;
  reversedInfinite[1][1] = -2.1f;
  reversedInfinite[2][3] = -1.0f;
  reversedInfinite[3][2] = 0.05f;
  const glm::mat4 projections[] = {glm::perspectiveRH_NO(glm::radians(45.0f), 1.5f, 0.5f, 4000.0f), vulkan, offCentre, reversedInfinite};
  const glm::mat4 views[] = {glm::mat4(1.0f), rigidView(0.7f, {1, 2, 3}, {4, -2, 9}), rigidView(3.0f, {0, 1, 0}, {-150, 30, 2000}),
                             glm::lookAtRH(glm::vec3(3, 5, 8), glm::vec3(0, 0, 0), glm::vec3(0, 1, 0))};
  for (const auto& p : projections)
    for (const auto& v : views) {
      const FactoredViewProjection f = factorViewProjection(p * v, "cb.view_projection");
      // Within the float rounding of the product's largest entry (the view's translation times the
      // projection's scale: a camera 2000 units out loses digits the factoring cannot restore).
      const double rounding = 8.0 * 1.2e-7 * largestDifference(p * v, glm::mat4(0.0f));
      EXPECT_LT(largestDifference(f.projection, p), rounding) << "projection";
      EXPECT_LT(largestDifference(f.view, v), 2e-3) << "view";
      EXPECT_LT(f.residual, 1e-6);
      EXPECT_EQ(f.projection[2][3], -1.0f);
      EXPECT_EQ(f.projection[0][1], 0.0f);
      EXPECT_EQ(f.projection[3][3], 0.0f);
      EXPECT_TRUE(properRotation(f.view));
    }
}

// A left-handed application (clip w = +z_view, as D3D's) has no right-handed factoring with the
// same view: the split gives a proper rotation 180 degrees about x from it and the same product.
TEST(ViewProjection, LeftHandedMatricesGiveAnEquivalentRightHandedPair) {
  const glm::mat4 p = glm::perspectiveLH_ZO(glm::radians(70.0f), 4.0f / 3.0f, 0.1f, 50.0f);
  const glm::mat4 v = glm::lookAtLH(glm::vec3(2, 3, -6), glm::vec3(0, 1, 0), glm::vec3(0, 1, 0));
  const FactoredViewProjection f = factorViewProjection(p * v, "cb0_0._child0[0]");
  EXPECT_LT(largestDifference(f.projection * f.view, p * v), 1e-5);
  EXPECT_TRUE(properRotation(f.view));
  EXPECT_GT(f.projection[0][0], 0.0f);
  EXPECT_LT(f.projection[1][1], 0.0f) << "y turned with z";
}

// P.V.M with a rigid model factors, the model folded into the view (world is then the object's frame).
TEST(ViewProjection, ARigidModelFoldsIntoTheView) {
  const glm::mat4 p = glm::perspectiveRH_ZO(glm::radians(50.0f), 1.0f, 0.2f, 80.0f);
  const glm::mat4 v = rigidView(0.4f, {0, 1, 0.2f}, {1, 2, 10});
  const glm::mat4 model = glm::translate(glm::mat4(1.0f), {3, 0, -1}) * glm::rotate(glm::mat4(1.0f), 1.1f, glm::vec3(0, 0, 1));
  const FactoredViewProjection f = factorViewProjection(p * v * model, "Object.mvp");
  EXPECT_LT(largestDifference(f.view, v * model), 1e-4);
  EXPECT_LT(largestDifference(f.projection, p), 1e-5);
}

TEST(ViewProjection, WhatIsNotAPerspectiveTimesARigidViewIsRefusedNamingWhatWasFound) {
  const glm::mat4 p = glm::perspectiveRH_ZO(glm::radians(50.0f), 1.0f, 0.2f, 80.0f);
  const glm::mat4 v = rigidView(0.4f, {0, 1, 0.2f}, {1, 2, 10});
  const glm::mat4 stretch = glm::scale(glm::mat4(1.0f), {1.0f, 2.0f, 1.0f}) * glm::rotate(glm::mat4(1.0f), 0.8f, glm::vec3(1, 1, 0));
  EXPECT_NE(problemOf(p * v * stretch).find("degrees from perpendicular (a shear or a non-uniform scale folded in"), std::string::npos)
      << problemOf(p * v * stretch);
  const glm::mat4 ortho = glm::orthoRH_ZO(-2.0f, 2.0f, -1.0f, 1.0f, 0.1f, 10.0f);
  EXPECT_NE(problemOf(ortho * v).find("cb.mvp has no perspective: its last row is (0, 0, 0, 1)"), std::string::npos)
      << problemOf(ortho * v);
  glm::mat4 mixed = p * v;
  mixed[0][2] += 0.3f;  // depth row leaning on x: no perspective times rigid view gives it
  EXPECT_NE(problemOf(mixed).find("the closest such product differs by"), std::string::npos) << problemOf(mixed);
  glm::mat4 infinite = p * v;
  infinite[1][1] = INFINITY;
  EXPECT_NE(problemOf(infinite).find("non-finite"), std::string::npos);
  EXPECT_NE(problemOf(glm::mat4(0.0f)).find("has no perspective"), std::string::npos);
}

}  // namespace
}  // namespace aor
