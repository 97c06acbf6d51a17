#pragma once
// The known scene rd_scene rasterises and the RenderDoc import tests check against: a floor and
// three boxes (one turned about the vertical axis), seen by a camera that orbits a little per
// frame. The program draws these triangles; the tests intersect the same shapes analytically.
#include <cmath>
#include <optional>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace aor::rdtest {

inline constexpr float kFloorHalfSize = 8.0f;  // the floor is y = 0, |x|, |z| <= this
inline constexpr float kNear = 0.1f;
inline constexpr float kFar = 40.0f;
inline constexpr float kVerticalFovDegrees = 60.0f;

struct Box {
  glm::vec2 centerXZ;
  glm::vec3 halfExtents;  // y: half the height; the box stands on the floor
  float yawRadians;       // turn about +Y
};

inline std::vector<Box> sceneBoxes() {
  return {{{-1.0f, -0.5f}, {0.5f, 0.6f, 0.5f}, 0.0f},
          {{0.8f, -0.1f}, {0.5f, 0.3f, 0.5f}, 0.5235988f},
          {{-0.1f, 1.1f}, {0.3f, 0.2f, 0.3f}, 0.0f}};
}

struct Vertex {
  glm::vec3 position;
  glm::vec3 normal;  // world space, per face
};

// Triangle lists: the floor first, then each box; `firstVertex[i]`..`firstVertex[i+1]` is object i.
struct SceneMesh {
  std::vector<Vertex> vertices;
  std::vector<uint32_t> firstVertex;
};

inline glm::mat3 boxRotation(const Box& b) {
  return glm::mat3(glm::rotate(glm::mat4(1.0f), b.yawRadians, glm::vec3(0, 1, 0)));
}

inline SceneMesh sceneMesh() {
  SceneMesh mesh;
  auto quad = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec3 n) {
    for (glm::vec3 p : {a, b, c, a, c, d}) mesh.vertices.push_back({p, n});
  };
  const float s = kFloorHalfSize;
  mesh.firstVertex.push_back(0);
  quad({-s, 0, -s}, {-s, 0, s}, {s, 0, s}, {s, 0, -s}, {0, 1, 0});
  for (const Box& box : sceneBoxes()) {
    mesh.firstVertex.push_back(uint32_t(mesh.vertices.size()));
    const glm::mat3 r = boxRotation(box);
    const glm::vec3 center(box.centerXZ.x, box.halfExtents.y, box.centerXZ.y);
    for (int axis = 0; axis < 3; ++axis)
      for (float side : {-1.0f, 1.0f}) {
        glm::vec3 n(0.0f), u(0.0f), v(0.0f);
        n[axis] = side;
        u[(axis + 1) % 3] = 1.0f;
        v[(axis + 2) % 3] = 1.0f;
        const glm::vec3 e = box.halfExtents;
        auto corner = [&](float a, float b) { return center + r * (n * e + a * u * e + b * v * e); };
        quad(corner(-1, -1), corner(1, -1), corner(1, 1), corner(-1, 1), r * n);
      }
  }
  mesh.firstVertex.push_back(uint32_t(mesh.vertices.size()));
  return mesh;
}

struct Camera {
  glm::mat4 view;        // world -> view, right-handed, looking down -Z
  glm::mat4 projection;  // view -> clip, Vulkan depth [0,1], y down
};

inline Camera sceneCamera(int frame, int width, int height, bool reversed) {
  const float angle = 0.6f + 0.05f * float(frame);
  const glm::vec3 eye(5.0f * std::sin(angle), 2.2f, 5.0f * std::cos(angle));
  Camera c;
  c.view = glm::lookAt(eye, glm::vec3(0.0f, 0.4f, 0.0f), glm::vec3(0, 1, 0));
  const float f = 1.0f / std::tan(glm::radians(kVerticalFovDegrees) * 0.5f);
  c.projection = glm::mat4(0.0f);
  c.projection[0][0] = f * float(height) / float(width);
  c.projection[1][1] = -f;
  c.projection[2][3] = -1.0f;
  c.projection[2][2] = reversed ? kNear / (kFar - kNear) : kFar / (kNear - kFar);
  c.projection[3][2] = reversed ? kNear * kFar / (kFar - kNear) : kNear * kFar / (kNear - kFar);
  return c;
}

// What the ray from the world-space `origin` along `dir` hits first: the distance along `dir`
// (in units of |dir|) and which surface (0 the floor, 1 + 6*box + face for a box face).
struct Hit {
  double t;
  int surface;
};

inline std::optional<Hit> intersectScene(glm::dvec3 origin, glm::dvec3 dir) {
  std::optional<Hit> best;
  auto consider = [&](double t, int surface) {
    if (t > 0.0 && (!best || t < best->t)) best = Hit{t, surface};
  };
  if (dir.y != 0.0) {
    const double t = -origin.y / dir.y;
    const glm::dvec3 p = origin + t * dir;
    if (std::abs(p.x) <= kFloorHalfSize && std::abs(p.z) <= kFloorHalfSize) consider(t, 0);
  }
  const auto boxes = sceneBoxes();
  for (size_t i = 0; i < boxes.size(); ++i) {
    const Box& b = boxes[i];
    const glm::dmat3 toLocal = glm::transpose(glm::dmat3(boxRotation(b)));
    const glm::dvec3 center(b.centerXZ.x, b.halfExtents.y, b.centerXZ.y);
    const glm::dvec3 o = toLocal * (origin - center), d = toLocal * dir, e(b.halfExtents);
    double tNear = -1e300, tFar = 1e300;
    int face = -1;
    for (int axis = 0; axis < 3; ++axis) {  // slabs; an axis-parallel ray outside a slab misses
      if (d[axis] == 0.0) {
        if (std::abs(o[axis]) > e[axis]) tFar = -1.0;
        continue;
      }
      double t0 = (-e[axis] - o[axis]) / d[axis], t1 = (e[axis] - o[axis]) / d[axis];
      const int entryFace = 2 * axis + (d[axis] > 0 ? 0 : 1);
      if (t0 > t1) std::swap(t0, t1);
      if (t0 > tNear) tNear = t0, face = entryFace;
      tFar = std::min(tFar, t1);
    }
    if (tNear <= tFar && face >= 0) consider(tNear, 1 + 6 * int(i) + face);
  }
  return best;
}

}  // namespace aor::rdtest
