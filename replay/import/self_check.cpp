#include "import/self_check.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/glm.hpp>

namespace aor {

namespace {

// A triangle corner in the capture's pixel coordinates (x right, y down from the capture's top
// edge), with its window depth and 1/w, which are both affine in screen space.
struct ScreenCorner {
  glm::dvec2 pixel;
  double depth = 0.0, inverseW = 0.0;
};

ScreenCorner toScreen(const SelfCheckInput& in, const glm::vec4& clip) {
  const double w = clip.w;
  const double column = double(in.viewport.x) + (clip.x / w + 1.0) * 0.5 * double(in.viewport.width);
  const double row = windowRow(in.conventions, in.viewport, clip.y / w);
  const ViewportRect& r = in.rect;
  const double y = in.conventions.rowsBottomUp ? double(r.y + r.height) - row : row - double(r.y);
  return {{column - double(r.x), y}, windowDepth(in.conventions, clip.z / w), 1.0 / w};
}

bool onScreen(const glm::vec4& c) {
  return c.w > 0.0f && std::abs(c.x) <= c.w && std::abs(c.y) <= c.w && std::abs(c.z) <= c.w;
}

// (a): clip z = P[2][2] z_view + P[3][2], with z_view = w / P[2][3] (P[2][3] is +-1).
double residualAt(const glm::vec4& c, const glm::mat4& p) {
  const double zView = double(c.w) / double(p[2][3]);
  const double predicted = double(p[2][2]) * zView + double(p[3][2]);
  return std::abs(double(c.z) - predicted) / double(c.w);
}

void checkDepthRow(const SelfCheckInput& in, SelfCheckResult& out) {
  for (const glm::vec4& c : in.corners) {
    if (!onScreen(c)) continue;
    ++out.verticesOnScreen;
    out.depthRowResidual = std::max(out.depthRowResidual, residualAt(c, in.appProjection));
  }
}

double edge(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& p) {
  return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
}

// Barycentric weights of `p`, or none when it lies within half a pixel of an edge (or outside):
// far beyond the rasteriser's sub-pixel snapping, so the point is this triangle's, whatever the
// API's rule for pixels on an edge.
bool innerWeights(const ScreenCorner* t, const glm::dvec2& p, double area, glm::dvec3& weights) {
  const glm::dvec2 a = t[0].pixel, b = t[1].pixel, c = t[2].pixel;
  const double e[3] = {edge(b, c, p) / area, edge(c, a, p) / area, edge(a, b, p) / area};
  const double lengths[3] = {glm::length(c - b), glm::length(a - c), glm::length(b - a)};
  for (int i = 0; i < 3; ++i)
    if (e[i] * std::abs(area) / lengths[i] < 0.5) return false;  // distance to edge i, in pixels
  weights = {e[0], e[1], e[2]};
  return true;
}

// The view distance the capture's projection gives depth d, and the d it gives distance s.
double captureDistance(const glm::mat4& p, double d) { return double(p[3][2]) / (d + double(p[2][2])); }
double captureDepth(const glm::mat4& p, double distance) { return double(p[3][2]) / distance - double(p[2][2]); }

void comparePoint(const SelfCheckInput& in, const ScreenCorner* t, const glm::dvec3& b, int x, int y,
                  double slope, SelfCheckResult& out) {
  const double drawnWindow = b.x * t[0].depth + b.y * t[1].depth + b.z * t[2].depth;
  if (drawnWindow < 0.0 || drawnWindow > 1.0) return;  // clipped away in depth
  const double distance = 1.0 / (b.x * t[0].inverseW + b.y * t[1].inverseW + b.z * t[2].inverseW);
  const double drawn = captureDepth(in.captureProjection, distance);
  const double imported = (*in.depth)[size_t(y) * size_t(in.rect.width) + size_t(x)];
  ++out.points;
  // One step of the format either way, float rounding, and the rasteriser's sub-pixel snapping.
  const double tolerance = 2.0 * in.depthQuantum + 1e-5 + 4.0 * 1.2e-7 * std::abs(drawn) + slope / 64.0;
  const double difference = std::abs(imported - drawn);
  if (difference <= tolerance) {
    ++out.matched;
    return;
  }
  const double importedDistance = captureDistance(in.captureProjection, imported);
  if (std::isfinite(importedDistance) && importedDistance > 0.0 && importedDistance < distance) {
    ++out.hidden;
    return;
  }
  ++out.disagreed;
  if (!(difference <= out.worstDifference)) {
    out.worstDifference = difference;
    out.worstX = x, out.worstY = y;
    out.worstImported = imported, out.worstDrawn = drawn;
  }
}

void sampleTriangle(const SelfCheckInput& in, const ScreenCorner* t, SelfCheckResult& out) {
  const double area = edge(t[0].pixel, t[1].pixel, t[2].pixel);
  if (std::abs(area) < 4.0) return;
  glm::dvec2 lo = glm::min(t[0].pixel, glm::min(t[1].pixel, t[2].pixel));
  glm::dvec2 hi = glm::max(t[0].pixel, glm::max(t[1].pixel, t[2].pixel));
  const int x0 = std::max(0, int(std::floor(lo.x))), x1 = std::min(in.rect.width - 1, int(std::floor(hi.x)));
  const int y0 = std::max(0, int(std::floor(lo.y))), y1 = std::min(in.rect.height - 1, int(std::floor(hi.y)));
  if (x0 > x1 || y0 > y1) return;
  const double span = double(x1 - x0 + 1) * double(y1 - y0 + 1);
  const int step = std::max(1, int(std::ceil(std::sqrt(span / kSelfCheckPointsPerTriangle))));
  // The plane's depth change per pixel, for the snapping allowance.
  const double slope = (std::abs(t[1].depth - t[0].depth) + std::abs(t[2].depth - t[0].depth)) /
                       std::max(1.0, std::min(glm::length(t[1].pixel - t[0].pixel), glm::length(t[2].pixel - t[0].pixel)));
  for (int y = y0 + step / 2; y <= y1; y += step)
    for (int x = x0 + step / 2; x <= x1; x += step) {
      glm::dvec3 b;
      if (innerWeights(t, glm::dvec2(x, y) + in.samplePosition, area, b)) comparePoint(in, t, b, x, y, slope, out);
    }
}

// The triangle's part in front of the eye (w >= a small fraction of its largest w), as a fan of
// triangles: z/w and 1/w stay affine over the visible part, so the points sampled in it are exact.
std::vector<glm::vec4> clipToFront(const glm::vec4* c) {
  const float wMax = std::max(c[0].w, std::max(c[1].w, c[2].w));
  if (!(wMax > 0.0f)) return {};
  const float wMin = 1e-5f * wMax;
  std::vector<glm::vec4> polygon;
  for (int i = 0; i < 3; ++i) {
    const glm::vec4 &a = c[i], &b = c[(i + 1) % 3];
    if (a.w >= wMin) polygon.push_back(a);
    if ((a.w >= wMin) != (b.w >= wMin)) polygon.push_back(a + (b - a) * ((wMin - a.w) / (b.w - a.w)));
  }
  std::vector<glm::vec4> fan;
  for (size_t i = 1; i + 1 < polygon.size(); ++i) fan.insert(fan.end(), {polygon[0], polygon[i], polygon[i + 1]});
  return fan;
}

}  // namespace

double depthRowResidual(const std::vector<glm::vec4>& corners, const glm::mat4& projection) {
  double largest = 0.0;
  for (const glm::vec4& c : corners)
    if (onScreen(c)) largest = std::max(largest, residualAt(c, projection));
  return largest;
}

bool SelfCheckResult::depthRowPassed() const { return depthRowResidual <= kSelfCheckMaxDepthRowResidual; }

bool SelfCheckResult::depthPassed() const {
  const size_t seen = matched + disagreed;
  return seen >= kSelfCheckMinPoints && double(matched) >= kSelfCheckMinMatchFraction * double(seen);
}

SelfCheckResult runSelfCheck(const SelfCheckInput& in) {
  SelfCheckResult out;
  out.vertices = in.corners.size();
  checkDepthRow(in, out);
  for (size_t i = 0; i + 2 < in.corners.size(); i += 3) {
    const std::vector<glm::vec4> front = clipToFront(&in.corners[i]);
    if (!front.empty()) ++out.triangles;
    for (size_t j = 0; j < front.size(); j += 3) {
      const ScreenCorner t[3] = {toScreen(in, front[j]), toScreen(in, front[j + 1]), toScreen(in, front[j + 2])};
      sampleTriangle(in, t, out);
    }
  }
  return out;
}

}  // namespace aor
