#include "import/renderdoc_camera.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <glm/glm.hpp>

#include "import/import_problem.h"

namespace aor {

namespace {

constexpr const char* kSeparateMatrices =
    "the import needs the world -> view matrix (--view) and the view -> clip projection (--projection) as separate "
    "members, or a combined view-projection matrix as --view-projection";
// Axes further from perpendicular than this are a shear or a non-uniform scale, not a rotation.
constexpr double kMaxSkewDegrees = 0.01;

std::string lastRow(const glm::mat4& m) {
  return fmt::format("({:g}, {:g}, {:g}, {:g})", m[0][3], m[1][3], m[2][3], m[3][3]);
}

void requireFinite(const glm::mat4& m, const std::string& name, const char* field) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r]))
        throw ImportProblem(field, fmt::format("{} has a non-finite entry (row {}, column {}: {})", name, r, c, m[c][r]));
}

}  // namespace

FactoredViewProjection factorViewProjection(const glm::mat4& combined, const std::string& name) {
  requireFinite(combined, name, "--view-projection");
  const glm::dmat4 m(combined);
  double largest = 0;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) largest = std::max(largest, std::abs(m[c][r]));
  auto row = [&](int r) { return glm::dvec4(m[0][r], m[1][r], m[2][r], m[3][r]); };
  // Clip w = -z_view: the last row is minus the view's z row, whose rotation part is a unit vector.
  const double lambda = glm::length(glm::dvec3(row(3)));
  if (!(lambda > 1e-6 * largest))
    throw ImportProblem("--view-projection", fmt::format("{} has no perspective: its last row is {}, so clip w does not "
                                                         "depend on the position (an orthographic projection); only "
                                                         "perspective projections are supported",
                                                         name, lastRow(combined)));
  const glm::dvec4 r0 = row(0) / lambda, r1 = row(1) / lambda, r2 = row(2) / lambda, r3 = row(3) / lambda;
  const glm::dvec3 z = -glm::dvec3(r3);
  const double tz = -r3.w;
  // Rows 0 and 1 are P[0][0] x + P[2][0] z and P[1][1] y + P[2][1] z (plus translations).
  const double offsetX = glm::dot(glm::dvec3(r0), z), offsetY = glm::dot(glm::dvec3(r1), z);
  glm::dvec3 x = glm::dvec3(r0) - offsetX * z, y = glm::dvec3(r1) - offsetY * z;
  const double sx = glm::length(x);
  double sy = glm::length(y);
  if (!(sx > 0 && sy > 0))
    throw ImportProblem("--view-projection", fmt::format("{} is singular: it maps every point to one screen line", name));
  x /= sx;
  y /= sy;
  if (glm::dot(glm::cross(x, y), z) < 0) {  // a proper rotation; the y flip goes into the projection
    y = -y;
    sy = -sy;
  }
  FactoredViewProjection f;
  f.skewDegrees = 90.0 - glm::degrees(std::acos(std::min(1.0, std::abs(glm::dot(x, y)))));
  if (f.skewDegrees > kMaxSkewDegrees)
    throw ImportProblem("--view-projection", fmt::format("{} is not a perspective projection times a rigid view: the "
                                                         "view's x and y axes are {:.3g} degrees from perpendicular (a "
                                                         "shear or a non-uniform scale folded in, e.g. a model matrix "
                                                         "that scales); at most {:g} degrees",
                                                         name, f.skewDegrees, kMaxSkewDegrees));
  const double tx = (r0.w - offsetX * tz) / sx, ty = (r1.w - offsetY * tz) / sy;
  const double depthScale = glm::dot(glm::dvec3(r2), z), depthOffset = r2.w - depthScale * tz;
  glm::dmat4 view(1.0), projection(0.0);
  for (int i = 0; i < 3; ++i) {
    view[i][0] = x[i];
    view[i][1] = y[i];
    view[i][2] = z[i];
  }
  view[3] = glm::dvec4(tx, ty, tz, 1.0);
  projection[0][0] = sx;
  projection[1][1] = sy;
  projection[2] = glm::dvec4(offsetX, offsetY, depthScale, -1.0);
  projection[3][2] = depthOffset;
  const glm::dmat4 product = projection * view;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) f.residual = std::max(f.residual, std::abs(product[c][r] - m[c][r] / lambda) * lambda / largest);
  if (f.residual > kMaxFactoringResidual)
    throw ImportProblem("--view-projection", fmt::format("{} is not a perspective projection times a rigid view: the "
                                                         "closest such product differs by {:.3g} of its largest entry "
                                                         "(at most {:g})",
                                                         name, f.residual, kMaxFactoringResidual));
  f.view = glm::mat4(view);
  f.projection = glm::mat4(projection);
  return f;
}

glm::mat4 matrixFromRows(const std::array<float, 16>& rows) {
  glm::mat4 m;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m[c][r] = rows[size_t(4 * r + c)];
  return m;
}

void checkViewMatrix(const glm::mat4& view, const std::string& name) {
  requireFinite(view, name, "--view");
  if (view[0][3] != 0.0f || view[1][3] != 0.0f || view[2][3] != 0.0f || view[3][3] != 1.0f)
    throw ImportProblem("--view", fmt::format("{} is not a world -> view transform: its last row is {}, a rigid or "
                                              "affine transform's is (0, 0, 0, 1); {}",
                                              name, lastRow(view), kSeparateMatrices));
  // As the capture format checks it: |det| against the product of the column lengths.
  const glm::dmat4 d(view);
  double scale = 1.0;
  for (int c = 0; c < 4; ++c) scale *= glm::length(d[c]);
  const double det = glm::determinant(d);
  if (!(std::abs(det) > 1e-12 * scale))
    throw ImportProblem("--view", fmt::format("{} is singular (determinant {:g}): not a world -> view transform", name,
                                              det));
}

void checkProjectionMatrix(const glm::mat4& p, const std::string& name) {
  requireFinite(p, name, "--projection");
  if (p[0][3] == 0.0f && p[1][3] == 0.0f && p[2][3] == 0.0f && p[3][3] == 1.0f)
    throw ImportProblem("--projection", fmt::format("{} is not a perspective projection: its last row is (0, 0, 0, 1), "
                                                    "an orthographic projection's (or no projection at all); only "
                                                    "perspective projections are supported",
                                                    name));
  if (p[0][3] != 0.0f || p[1][3] != 0.0f || std::abs(p[2][3]) != 1.0f || p[3][3] != 0.0f)
    throw ImportProblem("--projection", fmt::format("{} is not a perspective projection: its last row is {}, a "
                                                    "perspective projection's is (0, 0, -1, 0) (or (0, 0, 1, 0) "
                                                    "left-handed); {}",
                                                    name, lastRow(p), kSeparateMatrices));
  static const int zeros[][2] = {{0, 1}, {0, 2}, {1, 0}, {1, 2}, {3, 0}, {3, 1}};  // [column][row]
  for (const auto& z : zeros)
    if (p[z[0]][z[1]] != 0.0f)
      throw ImportProblem("--projection", fmt::format("{} is not a perspective projection: row {}, column {} is {:g} "
                                                      "where a perspective projection has 0; {}",
                                                      name, z[1], z[0], p[z[0]][z[1]], kSeparateMatrices));
  static const int nonZeros[][2] = {{0, 0}, {1, 1}, {3, 2}};
  for (const auto& z : nonZeros)
    if (p[z[0]][z[1]] == 0.0f)
      throw ImportProblem("--projection", fmt::format("{} is singular (row {}, column {} is 0)", name, z[1], z[0]));
}

ViewportRect viewportRect(float x, float y, float width, float height, float minDepth, float maxDepth,
                          int targetWidth, int targetHeight) {
  ViewportRect v;
  v.flipsY = height < 0.0f;
  const float top = v.flipsY ? y + height : y;  // a negative height counts up from y
  const float h = std::abs(height);
  const auto whole = [](float f) { return std::isfinite(f) && f == std::floor(f); };
  const std::string text = fmt::format("{:g}x{:g} at ({:g}, {:g})", width, height, x, y);
  if (!whole(x) || !whole(top) || !whole(width) || !whole(h) || width <= 0.0f || h <= 0.0f)
    throw ImportProblem("--event", fmt::format("the draw's viewport {} is not a whole-pixel rectangle: not supported",
                                               text));
  if (x < 0.0f || top < 0.0f || x + width > float(targetWidth) || top + h > float(targetHeight))
    throw ImportProblem("--event", fmt::format("the draw's viewport {} reaches outside the {}x{} depth target", text,
                                               targetWidth, targetHeight));
  // Any other range is folded into the projection (api_conventions.h); an empty one stores one value.
  if (!std::isfinite(minDepth) || !std::isfinite(maxDepth) || minDepth == maxDepth || minDepth < 0.0f || minDepth > 1.0f ||
      maxDepth < 0.0f || maxDepth > 1.0f)
    throw ImportProblem("--event", fmt::format("the draw's viewport maps depth to [{:g}, {:g}]: every depth it stores "
                                               "is one value, or outside [0, 1]",
                                               minDepth, maxDepth));
  v.x = int(x), v.y = int(top), v.width = int(width), v.height = int(h);
  return v;
}

ImportedCamera importCamera(const glm::mat4& view, const glm::mat4& projection, bool clipYUpAtTopRow) {
  ImportedCamera c{view, projection, {}};
  if (projection[2][3] == 1.0f) {  // left-handed: S = diag(1, 1, -1, 1); view' = S view, projection' = P S
    for (int col = 0; col < 4; ++col) c.view[col][2] = -c.view[col][2];
    c.projection[2] = -c.projection[2];
    c.adjustments.push_back("left-handed view space: z flipped in view and projection");
  }
  if (clipYUpAtTopRow) {  // F = diag(1, -1, 1, 1): projection' = F P
    for (int col = 0; col < 4; ++col) c.projection[col][1] = -c.projection[col][1];
    c.adjustments.push_back("NDC y = +1 at the top row: projection y flipped");
  }
  return c;
}

std::string describeProjection(const glm::mat4& p, double depthA, double depthB) {
  const bool reversed = p[3][2] > 0.0f;
  const double p22 = p[2][2], p32 = p[3][2];
  // Window depth at view distance t: d = P32 / t - P22, so t = P32 / (d + P22); the near and far
  // planes are where d reaches the ends of the depth range the projection maps to.
  auto distance = [&](double d) {
    const double t = d + p22 == 0.0 ? INFINITY : p32 / (d + p22);
    return t < 0.0 ? INFINITY : t;
  };
  const double nearPlane = std::min(distance(depthA), distance(depthB));
  const double farPlane = std::max(distance(depthA), distance(depthB));
  const double fov = 2.0 * std::atan(1.0 / std::abs(double(p[1][1]))) * 180.0 / M_PI;
  return fmt::format("perspective, {} depth, near {:.4g}, far {:.4g}, vertical field of view {:.1f} degrees",
                     reversed ? "reversed" : "standard", nearPlane, farPlane, fov);
}

void viewNormalsToWorld(std::vector<float>& normals, const glm::mat4& view) {
  const glm::mat3 worldFromView = glm::transpose(glm::mat3(view));
  for (size_t i = 0; i + 2 < normals.size(); i += 3) {
    const glm::vec3 n(normals[i], normals[i + 1], normals[i + 2]);
    if (n == glm::vec3(0.0f)) continue;  // an empty (cleared) texel stays empty
    const glm::vec3 w = glm::normalize(worldFromView * n);
    normals[i] = w.x, normals[i + 1] = w.y, normals[i + 2] = w.z;
  }
}

}  // namespace aor
