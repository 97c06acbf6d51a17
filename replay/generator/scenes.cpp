// Scene geometry for the synthetic generator: analytic primitives (Embree user geometry, exact in
// double precision) and triangle meshes (axis-aligned boxes, walls, the Stanford bunny).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>
#include <tiny_obj_loader.h>

#include "core/input_error.h"
#include "generator/generator_internal.h"

namespace aor::gen {
namespace {

using glm::dvec3;

constexpr double kFloorHalfSize = 5000.0;  // "infinite-ish" floor: 1e4 m wide

// ---- Analytic primitives ----------------------------------------------------------------------

enum class PrimKind { Floor, Disc, Cylinder, Sphere };

struct AnalyticPrim {
  PrimKind kind = PrimKind::Floor;
  // Floor/Disc: (cx, y, cz) of the plane; Cylinder: (cx, y0, cz) of the bottom; Sphere: centre.
  dvec3 centre{0.0};
  // Floor: radius of a circular hole (0: none); Disc/Cylinder/Sphere: radius.
  double radius = 0.0;
  // Floor: half size of the square; Cylinder: height (y1 = y0 + extent).
  double extent = 0.0;
};

// Roots of a t^2 + 2 b t + c = 0 in ascending order (numerically stable form).
int solveQuadratic(double a, double b, double c, double t[2]) {
  if (a == 0.0) return 0;
  const double disc = b * b - a * c;
  if (disc < 0.0) return 0;
  const double s = std::sqrt(disc);
  const double q = -(b + std::copysign(s, b));
  if (q == 0.0) {
    t[0] = t[1] = 0.0;
    return 2;
  }
  double t0 = q / a, t1 = c / q;
  if (t0 > t1) std::swap(t0, t1);
  t[0] = t0;
  t[1] = t1;
  return 2;
}

// Parameters along origin + t*dir where the ray meets the primitive's surface, ascending.
int primRoots(const AnalyticPrim& p, const dvec3& o, const dvec3& d, double out[2]) {
  switch (p.kind) {
    case PrimKind::Floor:
    case PrimKind::Disc: {
      if (d.y == 0.0) return 0;
      const double t = (p.centre.y - o.y) / d.y;
      const double x = o.x + t * d.x - p.centre.x;
      const double z = o.z + t * d.z - p.centre.z;
      const double r2 = x * x + z * z;
      if (p.kind == PrimKind::Floor) {
        if (std::abs(x) > p.extent || std::abs(z) > p.extent || r2 < p.radius * p.radius) return 0;
      } else if (r2 > p.radius * p.radius) {
        return 0;
      }
      out[0] = t;
      return 1;
    }
    case PrimKind::Cylinder: {
      const double ox = o.x - p.centre.x, oz = o.z - p.centre.z;
      double t[2];
      if (solveQuadratic(d.x * d.x + d.z * d.z, ox * d.x + oz * d.z, ox * ox + oz * oz - p.radius * p.radius,
                         t) == 0)
        return 0;
      int n = 0;
      for (double ti : t) {
        const double y = o.y + ti * d.y;
        if (y >= p.centre.y && y <= p.centre.y + p.extent) out[n++] = ti;
      }
      return n;
    }
    case PrimKind::Sphere: {
      const dvec3 oc = o - p.centre;
      double t[2];
      if (solveQuadratic(glm::dot(d, d), glm::dot(oc, d), glm::dot(oc, oc) - p.radius * p.radius, t) == 0)
        return 0;
      out[0] = t[0];
      out[1] = t[1];
      return 2;
    }
  }
  return 0;
}

dvec3 primNormal(const AnalyticPrim& p, const dvec3& pos) {
  switch (p.kind) {
    case PrimKind::Floor:
    case PrimKind::Disc:
      return {0.0, 1.0, 0.0};
    case PrimKind::Cylinder:
      return glm::normalize(dvec3(pos.x - p.centre.x, 0.0, pos.z - p.centre.z));
    case PrimKind::Sphere:
      return glm::normalize(pos - p.centre);
  }
  return {0.0, 1.0, 0.0};
}

void primBoundsD(const AnalyticPrim& p, dvec3& lo, dvec3& hi) {
  switch (p.kind) {
    case PrimKind::Floor:
      lo = {p.centre.x - p.extent, p.centre.y, p.centre.z - p.extent};
      hi = {p.centre.x + p.extent, p.centre.y, p.centre.z + p.extent};
      break;
    case PrimKind::Disc:
      lo = {p.centre.x - p.radius, p.centre.y, p.centre.z - p.radius};
      hi = {p.centre.x + p.radius, p.centre.y, p.centre.z + p.radius};
      break;
    case PrimKind::Cylinder:
      lo = {p.centre.x - p.radius, p.centre.y, p.centre.z - p.radius};
      hi = {p.centre.x + p.radius, p.centre.y + p.extent, p.centre.z + p.radius};
      break;
    case PrimKind::Sphere:
      lo = p.centre - dvec3(p.radius);
      hi = p.centre + dvec3(p.radius);
      break;
  }
}

void embreeBounds(const RTCBoundsFunctionArguments* args) {
  const auto& prims = *static_cast<const std::vector<AnalyticPrim>*>(args->geometryUserPtr);
  dvec3 lo(0.0), hi(0.0);
  primBoundsD(prims[args->primID], lo, hi);
  // Conservative float bounds.
  const double pad = 1e-4 * (1.0 + std::max(glm::length(lo), glm::length(hi)));
  args->bounds_o->lower_x = static_cast<float>(lo.x - pad);
  args->bounds_o->lower_y = static_cast<float>(lo.y - pad);
  args->bounds_o->lower_z = static_cast<float>(lo.z - pad);
  args->bounds_o->upper_x = static_cast<float>(hi.x + pad);
  args->bounds_o->upper_y = static_cast<float>(hi.y + pad);
  args->bounds_o->upper_z = static_cast<float>(hi.z + pad);
}

// First root in [tnear, tfar]; false if none.
bool primFirstHit(const AnalyticPrim& p, const dvec3& o, const dvec3& d, double tnear, double tfar, double& t) {
  double roots[2];
  const int n = primRoots(p, o, d, roots);
  for (int k = 0; k < n; ++k) {
    if (roots[k] >= tnear && roots[k] <= tfar) {
      t = roots[k];
      return true;
    }
  }
  return false;
}

void embreeIntersect(const RTCIntersectFunctionNArguments* args) {
  const auto& prim = (*static_cast<const std::vector<AnalyticPrim>*>(args->geometryUserPtr))[args->primID];
  const unsigned N = args->N;
  RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, N);
  RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, N);
  for (unsigned i = 0; i < N; ++i) {
    if (!args->valid[i]) continue;
    const dvec3 o(RTCRayN_org_x(ray, N, i), RTCRayN_org_y(ray, N, i), RTCRayN_org_z(ray, N, i));
    const dvec3 d(RTCRayN_dir_x(ray, N, i), RTCRayN_dir_y(ray, N, i), RTCRayN_dir_z(ray, N, i));
    double t = 0.0;
    if (!primFirstHit(prim, o, d, RTCRayN_tnear(ray, N, i), RTCRayN_tfar(ray, N, i), t)) continue;
    const dvec3 n = primNormal(prim, o + t * d);
    RTCRayN_tfar(ray, N, i) = static_cast<float>(t);
    RTCHitN_Ng_x(hit, N, i) = static_cast<float>(n.x);
    RTCHitN_Ng_y(hit, N, i) = static_cast<float>(n.y);
    RTCHitN_Ng_z(hit, N, i) = static_cast<float>(n.z);
    RTCHitN_u(hit, N, i) = 0.0f;
    RTCHitN_v(hit, N, i) = 0.0f;
    RTCHitN_primID(hit, N, i) = args->primID;
    RTCHitN_geomID(hit, N, i) = args->geomID;
    RTCHitN_instID(hit, N, i, 0) = args->context->instID[0];
  }
}

void embreeOccluded(const RTCOccludedFunctionNArguments* args) {
  const auto& prim = (*static_cast<const std::vector<AnalyticPrim>*>(args->geometryUserPtr))[args->primID];
  const unsigned N = args->N;
  RTCRayN* ray = args->ray;
  for (unsigned i = 0; i < N; ++i) {
    if (!args->valid[i]) continue;
    const dvec3 o(RTCRayN_org_x(ray, N, i), RTCRayN_org_y(ray, N, i), RTCRayN_org_z(ray, N, i));
    const dvec3 d(RTCRayN_dir_x(ray, N, i), RTCRayN_dir_y(ray, N, i), RTCRayN_dir_z(ray, N, i));
    double t = 0.0;
    if (primFirstHit(prim, o, d, RTCRayN_tnear(ray, N, i), RTCRayN_tfar(ray, N, i), t))
      RTCRayN_tfar(ray, N, i) = -std::numeric_limits<float>::infinity();
  }
}

// ---- Triangle meshes --------------------------------------------------------------------------

struct Mesh {
  std::vector<float> vertices;  // xyz, plus padding for Embree's 16-byte loads
  std::vector<uint32_t> indices;

  uint32_t vertex(const dvec3& p) {
    const uint32_t id = static_cast<uint32_t>(vertices.size() / 3);
    vertices.push_back(static_cast<float>(p.x));
    vertices.push_back(static_cast<float>(p.y));
    vertices.push_back(static_cast<float>(p.z));
    return id;
  }
  void triangle(uint32_t a, uint32_t b, uint32_t c) {
    indices.insert(indices.end(), {a, b, c});
  }
  // Quad a-b-c-d (in order around the outline).
  void quad(const dvec3& a, const dvec3& b, const dvec3& c, const dvec3& d) {
    const uint32_t ia = vertex(a), ib = vertex(b), ic = vertex(c), id = vertex(d);
    triangle(ia, ib, ic);
    triangle(ia, ic, id);
  }
  // Axis-aligned box; the bottom face is omitted when it rests on something (never visible).
  void box(const dvec3& lo, const dvec3& hi, bool bottom = false) {
    const dvec3 p[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, lo.y, hi.z}, {lo.x, lo.y, hi.z},
                        {lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
    quad(p[4], p[7], p[6], p[5]);  // top
    if (bottom) quad(p[0], p[1], p[2], p[3]);
    quad(p[0], p[4], p[5], p[1]);  // -z
    quad(p[3], p[2], p[6], p[7]);  // +z
    quad(p[0], p[3], p[7], p[4]);  // -x
    quad(p[1], p[5], p[6], p[2]);  // +x
  }
  size_t triangleCount() const { return indices.size() / 3; }
};

// Deterministic generator for scene layouts (splitmix64; std distributions are not portable).
struct LayoutRng {
  uint64_t state;
  explicit LayoutRng(uint64_t seed) : state(seed) {}
  uint64_t next() {
    uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  double uniform(double a, double b) { return a + (b - a) * static_cast<double>(next() >> 11) * 0x1.0p-53; }
  bool chance(double p) { return uniform(0.0, 1.0) < p; }
};

AnalyticPrim floorPrim(double holeRadius = 0.0) {
  AnalyticPrim p;
  p.kind = PrimKind::Floor;
  p.radius = holeRadius;
  p.extent = kFloorHalfSize;
  return p;
}

// City block: 4 x 4 lots of 3.4 m separated by 1.2 m streets (streets centred on x = 0 and z = 0
// stay clear, the camera paths use them). Lots hold buildings (some with upper tiers and thin
// awnings), walled courtyards with 5 cm walls and crates, or plazas with a roof on pillars.
void buildBoxes(Mesh& mesh) {
  LayoutRng rng(0x5eed0b0c5ull);
  const double lot = 3.4, street = 1.2, origin = -(4 * lot + 3 * street) / 2.0;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      const double x0 = origin + i * (lot + street), z0 = origin + j * (lot + street);
      const double x1 = x0 + lot, z1 = z0 + lot;
      const double kind = rng.uniform(0.0, 1.0);
      if (kind < 0.5) {
        // Buildings.
        const int count = 1 + static_cast<int>(rng.uniform(0.0, 3.0));
        for (int k = 0; k < count; ++k) {
          const double w = rng.uniform(0.8, 2.2), d = rng.uniform(0.8, 2.2), h = rng.uniform(0.6, 4.0);
          const double bx = x0 + rng.uniform(0.1, lot - w - 0.1), bz = z0 + rng.uniform(0.1, lot - d - 0.1);
          mesh.box({bx, 0.0, bz}, {bx + w, h, bz + d});
          if (rng.chance(0.4)) {
            const double inset = rng.uniform(0.15, 0.35);
            mesh.box({bx + inset, h, bz + inset}, {bx + w - inset, h + rng.uniform(0.4, 1.2), bz + d - inset});
          }
          if (rng.chance(0.35) && h > 1.2) {
            // Thin awning over the +x or -z side, kept inside the lot.
            const double ay = std::min(h - 0.3, rng.uniform(0.9, 2.2));
            if (rng.chance(0.5)) {
              const double ax1 = std::min(x1 - 0.02, bx + w + 0.6);
              if (ax1 > bx + w + 0.1) mesh.box({bx + w, ay, bz + 0.1}, {ax1, ay + 0.05, bz + d - 0.1}, true);
            } else {
              const double az0 = std::max(z0 + 0.02, bz - 0.6);
              if (az0 < bz - 0.1) mesh.box({bx + 0.1, ay, az0}, {bx + w - 0.1, ay + 0.05, bz}, true);
            }
          }
        }
      } else if (kind < 0.75) {
        // Courtyard: 5 cm walls around the lot with a gate, crates inside.
        const double h = rng.uniform(1.0, 2.2), t = 0.05, m = 0.1;
        const double gate0 = rng.uniform(x0 + 0.5, x1 - 1.4), gate1 = gate0 + 0.8;
        mesh.box({x0 + m, 0.0, z0 + m}, {x1 - m, h, z0 + m + t});
        mesh.box({x0 + m, 0.0, z1 - m - t}, {gate0, h, z1 - m});
        mesh.box({gate1, 0.0, z1 - m - t}, {x1 - m, h, z1 - m});
        mesh.box({x0 + m, 0.0, z0 + m + t}, {x0 + m + t, h, z1 - m - t});
        mesh.box({x1 - m - t, 0.0, z0 + m + t}, {x1 - m, h, z1 - m - t});
        const int crates = 3 + static_cast<int>(rng.uniform(0.0, 4.0));
        for (int k = 0; k < crates; ++k) {
          const double s = rng.uniform(0.2, 0.6);
          const double cx = rng.uniform(x0 + 0.2, x1 - 0.2 - s), cz = rng.uniform(z0 + 0.2, z1 - 0.2 - s);
          mesh.box({cx, 0.0, cz}, {cx + s, rng.uniform(0.2, 0.7), cz + s});
        }
        // A thin interior dividing wall.
        const double wx = rng.uniform(x0 + 1.0, x1 - 1.0);
        mesh.box({wx, 0.0, z0 + m + t}, {wx + t, h * 0.8, z0 + lot * 0.55});
      } else {
        // Plaza: roof slab on four slim pillars, benches, a kiosk.
        const double rx0 = x0 + rng.uniform(0.2, 0.6), rz0 = z0 + rng.uniform(0.2, 0.6);
        const double rx1 = x1 - rng.uniform(0.8, 1.4), rz1 = z1 - rng.uniform(0.8, 1.4);
        const double ry = rng.uniform(2.0, 2.8), p = 0.12;
        for (const auto& [px, pz] : {std::pair{rx0, rz0}, {rx1 - p, rz0}, {rx0, rz1 - p}, {rx1 - p, rz1 - p}})
          mesh.box({px, 0.0, pz}, {px + p, ry, pz + p});
        mesh.box({rx0 - 0.1, ry, rz0 - 0.1}, {rx1 + 0.1, ry + 0.08, rz1 + 0.1}, true);
        for (int k = 0; k < 2; ++k) {
          const double bx = rng.uniform(x0 + 0.3, x1 - 1.5), bz = rng.uniform(z0 + 0.3, z1 - 0.6);
          mesh.box({bx, 0.42, bz}, {bx + 1.2, 0.47, bz + 0.4}, true);  // seat
          mesh.box({bx + 0.05, 0.0, bz + 0.05}, {bx + 0.1, 0.42, bz + 0.35});
          mesh.box({bx + 1.1, 0.0, bz + 0.05}, {bx + 1.15, 0.42, bz + 0.35});
        }
        const double kx = x1 - 0.9, kz = z1 - 0.9;
        mesh.box({kx, 0.0, kz}, {kx + 0.7, rng.uniform(1.2, 2.0), kz + 0.7});
      }
    }
  }
}

// Rows of 4 cm poles, a thin horizontal rail along the front row, and a fence of 2 cm slats.
void buildThin(Mesh& mesh) {
  const double pole = 0.02;  // half width: "radius" 2 cm
  for (int row = 0; row < 3; ++row) {
    const double z = -0.8 + 0.8 * row;
    const double shift = (row % 2) ? 0.2 : 0.0;
    for (int k = 0; k < 15; ++k) {
      const double x = -2.8 + 0.4 * k + shift;
      mesh.box({x - pole, 0.0, z - pole}, {x + pole, 2.0, z + pole});
    }
  }
  // Rail between the poles of the front row.
  mesh.box({-2.8, 1.0, 0.8 - 0.01}, {2.8, 1.02, 0.8 + 0.01}, true);
  // Fence: slats 8 cm wide, 2 cm thick, 1.2 m tall, 6 cm gaps, two rails behind.
  for (double x = -3.0; x < 3.0 - 1e-9; x += 0.14) mesh.box({x, 0.0, -2.01}, {x + 0.08, 1.2, -1.99});
  mesh.box({-3.05, 0.25, -2.05}, {3.0, 0.31, -2.01}, true);
  mesh.box({-3.05, 0.95, -2.05}, {3.0, 1.01, -2.01}, true);
}

// Room (floor + back and side walls) around the Stanford bunny scaled to 1 m.
void buildBunny(Mesh& mesh, const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
    throw InputError(path.string(), std::nullopt, "scene",
                     "bunny model not found; install the Debian package glmark2-data "
                     "(apt-get install glmark2-data), which ships it");
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, path.string().c_str(), nullptr, true))
    throw InputError(path.string(), std::nullopt, "scene", "cannot parse OBJ: " + err);
  if (attrib.vertices.empty())
    throw InputError(path.string(), std::nullopt, "scene", "OBJ has no vertices");
  dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  const size_t nv = attrib.vertices.size() / 3;
  for (size_t v = 0; v < nv; ++v) {
    const dvec3 p(attrib.vertices[3 * v], attrib.vertices[3 * v + 1], attrib.vertices[3 * v + 2]);
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const dvec3 ext = hi - lo;
  const double scale = 1.0 / std::max({ext.x, ext.y, ext.z});
  const dvec3 offset(-(lo.x + hi.x) / 2.0, -lo.y, -(lo.z + hi.z) / 2.0);
  const uint32_t base = static_cast<uint32_t>(mesh.vertices.size() / 3);
  for (size_t v = 0; v < nv; ++v) {
    const dvec3 p(attrib.vertices[3 * v], attrib.vertices[3 * v + 1], attrib.vertices[3 * v + 2]);
    mesh.vertex((p + offset) * scale);
  }
  for (const auto& shape : shapes) {
    size_t index = 0;
    for (const auto fv : shape.mesh.num_face_vertices) {
      if (fv == 3) {
        const auto& ix = shape.mesh.indices;
        const int a = ix[index].vertex_index, b = ix[index + 1].vertex_index, c = ix[index + 2].vertex_index;
        if (a >= 0 && b >= 0 && c >= 0 && static_cast<size_t>(std::max({a, b, c})) < nv)
          mesh.triangle(base + a, base + b, base + c);
      }
      index += fv;
    }
  }
  // Walls (two-sided quads): back at z = -1.5, sides at x = +-1.8, 2.4 m high; open towards +z.
  const double bx = 1.8, bz = -1.5, fz = 2.4, h = 2.4;
  mesh.quad({-bx, 0, bz}, {bx, 0, bz}, {bx, h, bz}, {-bx, h, bz});
  mesh.quad({-bx, 0, bz}, {-bx, h, bz}, {-bx, h, fz}, {-bx, 0, fz});
  mesh.quad({bx, 0, bz}, {bx, 0, fz}, {bx, h, fz}, {bx, h, bz});
}

}  // namespace

std::filesystem::path defaultBunnyPath() { return "/usr/share/glmark2/models/bunny.obj"; }

std::vector<std::string> sceneNames() { return {"plane", "pit", "sphere", "boxes", "bunny", "thin"}; }

SceneInfo sceneInfo(const std::string& name) {
  SceneInfo s;
  s.name = name;
  if (name == "plane") {
    s.defaultRadius = 1.0;
    s.oracle = "visibility 1 everywhere (nothing but the floor)";
    s.focus = {0, 0, 0};
    s.distance = 6.0;
    s.height = 2.0;
    s.cutEye = {0.0, 0.25, 0.0};
    s.cutTarget = {10.0, 0.0, 4.0};
    s.strafeEye = {0.0, 1.5, 5.0};
    s.strafeTarget = {0.0, 0.0, 0.0};
    s.strafeSpan = 4.0;
  } else if (name == "pit") {
    s.defaultRadius = 2.0;
    s.oracle =
        "cylindrical pit radius a=1, depth H=1 centred at the origin (floor y=0, bottom y=-1): at the "
        "bottom centre visibility = a^2/(a^2+H^2) = 0.5 for R >= sqrt(a^2+H^2)";
    s.focus = {0, -0.6, 0};
    s.distance = 2.4;
    s.height = 2.2;
    s.cutEye = {0.4, 2.2, 0.3};
    s.cutTarget = {0.0, -1.0, 0.0};
    s.strafeEye = {0.0, 1.4, 2.6};
    s.strafeTarget = {0.0, -0.7, 0.0};
    s.strafeSpan = 2.5;
  } else if (name == "sphere") {
    s.defaultRadius = 100.0;
    s.oracle =
        "sphere r=1 centred at (0,1,0) on the floor: on the floor at horizontal distance x from the "
        "contact point visibility = 1 - r^3/(x^2+r^2)^(3/2) (unlimited R; R=100 is close enough)";
    s.focus = {0, 0.8, 0};
    s.distance = 4.0;
    s.height = 2.2;
    s.cutEye = {1.2, 4.0, 1.0};
    s.cutTarget = {0.0, 0.0, 0.0};
    s.strafeEye = {0.0, 1.0, 4.5};
    s.strafeTarget = {0.0, 0.8, 0.0};
    s.strafeSpan = 4.0;
  } else if (name == "boxes") {
    s.defaultRadius = 1.0;
    s.focus = {0, 0.5, 0};
    s.distance = 13.0;
    s.height = 6.0;
    s.cutEye = {0.0, 1.6, 8.0};  // street level in the street along x = 0
    s.cutTarget = {0.0, 1.2, -6.0};
    s.strafeEye = {0.0, 1.7, 12.0};
    s.strafeTarget = {0.0, 1.0, 0.0};
    s.strafeSpan = 7.0;
  } else if (name == "bunny") {
    s.defaultRadius = 0.5;
    s.focus = {0, 0.4, 0};
    s.distance = 1.9;
    s.height = 1.15;
    s.cutEye = {-1.4, 1.9, -1.1};
    s.cutTarget = {0.1, 0.35, 0.2};
    s.strafeEye = {0.0, 0.55, 1.7};
    s.strafeTarget = {0.0, 0.4, 0.0};
    s.strafeSpan = 1.8;
  } else if (name == "thin") {
    s.defaultRadius = 1.0;
    s.focus = {0, 0.6, -0.6};
    s.distance = 4.0;
    s.height = 1.6;
    s.cutEye = {4.2, 0.35, 0.4};
    s.cutTarget = {-3.0, 0.5, -1.2};
    s.strafeEye = {0.0, 1.2, 3.2};
    s.strafeTarget = {0.0, 0.6, -2.0};
    s.strafeSpan = 3.0;
  } else {
    std::string names;
    for (const auto& n : sceneNames()) names += (names.empty() ? "" : ", ") + n;
    throw InputError("", std::nullopt, "scene", "unknown scene '" + name + "' (expected one of: " + names + ")");
  }
  return s;
}

struct RayScene::Impl {
  SceneInfo info;
  Mesh mesh;
  std::vector<AnalyticPrim> prims;
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  unsigned meshGeom = RTC_INVALID_GEOMETRY_ID;
  unsigned primGeom = RTC_INVALID_GEOMETRY_ID;
  dvec3 meshMax{0.0};

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }

  void checkDevice(const char* what) const {
    const RTCError e = rtcGetDeviceError(device);
    if (e != RTC_ERROR_NONE) throw std::runtime_error(std::string("Embree error ") + std::to_string(e) + " in " + what);
  }

  void commit() {
    // One build thread: keeps the BVH (and so the choice between exactly tied hits) independent of
    // the machine's thread count. Builds are small, queries run on our own threads.
    device = rtcNewDevice("threads=1");
    if (!device) throw std::runtime_error("rtcNewDevice failed (Embree error " + std::to_string(rtcGetDeviceError(nullptr)) + ")");
    scene = rtcNewScene(device);
    rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
    if (mesh.triangleCount() > 0) {
      const size_t nv = mesh.vertices.size() / 3;
      dvec3 meshMin(std::numeric_limits<double>::max());
      meshMax = -meshMin;
      for (size_t v = 0; v < nv; ++v) {
        const dvec3 p(mesh.vertices[3 * v], mesh.vertices[3 * v + 1], mesh.vertices[3 * v + 2]);
        meshMin = glm::min(meshMin, p);
        meshMax = glm::max(meshMax, p);
      }
      mesh.vertices.push_back(0.0f);  // Embree reads vertices with 16-byte loads
      RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
      rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, mesh.vertices.data(), 0,
                                 3 * sizeof(float), nv);
      rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, mesh.indices.data(), 0,
                                 3 * sizeof(uint32_t), mesh.triangleCount());
      rtcCommitGeometry(g);
      meshGeom = rtcAttachGeometry(scene, g);
      rtcReleaseGeometry(g);
    }
    if (!prims.empty()) {
      RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
      rtcSetGeometryUserPrimitiveCount(g, static_cast<unsigned>(prims.size()));
      rtcSetGeometryUserData(g, &prims);
      rtcSetGeometryBoundsFunction(g, embreeBounds, nullptr);
      rtcSetGeometryIntersectFunction(g, embreeIntersect);
      rtcSetGeometryOccludedFunction(g, embreeOccluded);
      rtcCommitGeometry(g);
      primGeom = rtcAttachGeometry(scene, g);
      rtcReleaseGeometry(g);
    }
    rtcCommitScene(scene);
    checkDevice("scene build");
  }

  // Double-precision hit on the primitive Embree reported.
  SurfaceHit refine(unsigned geomID, unsigned primID, float tEmbree, const dvec3& o, const dvec3& d) const {
    SurfaceHit h;
    double t = tEmbree;
    dvec3 n(0.0, 1.0, 0.0);
    if (geomID == meshGeom) {
      const uint32_t* ix = &mesh.indices[3 * static_cast<size_t>(primID)];
      auto vtx = [&](uint32_t k) {
        return dvec3(mesh.vertices[3 * k], mesh.vertices[3 * k + 1], mesh.vertices[3 * k + 2]);
      };
      const dvec3 v0 = vtx(ix[0]), v1 = vtx(ix[1]), v2 = vtx(ix[2]);
      const dvec3 ng = glm::cross(v1 - v0, v2 - v0);
      const double denom = glm::dot(ng, d);
      if (denom != 0.0) t = glm::dot(ng, v0 - o) / denom;
      const double len = glm::length(ng);
      n = len > 0.0 ? ng / len : dvec3(0.0, 1.0, 0.0);  // degenerate triangles are never hit
    } else {
      const AnalyticPrim& p = prims[primID];
      double roots[2];
      const int k = primRoots(p, o, d, roots);
      double best = std::numeric_limits<double>::infinity();
      for (int r = 0; r < k; ++r) {
        if (std::abs(roots[r] - tEmbree) < best) {
          best = std::abs(roots[r] - tEmbree);
          t = roots[r];
        }
      }
      n = primNormal(p, o + t * d);
    }
    h.t = t;
    h.position = o + t * d;
    h.normal = glm::dot(n, d) > 0.0 ? -n : n;
    return h;
  }
};

RayScene::RayScene(const std::string& name, const std::filesystem::path& bunnyObj) : impl_(std::make_unique<Impl>()) {
  impl_->info = sceneInfo(name);
  auto& prims = impl_->prims;
  auto& mesh = impl_->mesh;
  if (name == "plane") {
    prims.push_back(floorPrim());
  } else if (name == "pit") {
    prims.push_back(floorPrim(1.0));
    AnalyticPrim wall;
    wall.kind = PrimKind::Cylinder;
    wall.centre = {0.0, -1.0, 0.0};
    wall.radius = 1.0;
    wall.extent = 1.0;
    prims.push_back(wall);
    AnalyticPrim bottom;
    bottom.kind = PrimKind::Disc;
    bottom.centre = {0.0, -1.0, 0.0};
    bottom.radius = 1.0;
    prims.push_back(bottom);
  } else if (name == "sphere") {
    prims.push_back(floorPrim());
    AnalyticPrim sphere;
    sphere.kind = PrimKind::Sphere;
    sphere.centre = {0.0, 1.0, 0.0};
    sphere.radius = 1.0;
    prims.push_back(sphere);
  } else if (name == "boxes") {
    prims.push_back(floorPrim());
    buildBoxes(mesh);
  } else if (name == "bunny") {
    prims.push_back(floorPrim());
    buildBunny(mesh, bunnyObj);
  } else if (name == "thin") {
    prims.push_back(floorPrim());
    buildThin(mesh);
  }
  impl_->commit();
}

namespace {

// The analytic primitives as triangles (RayScene::triangles): the same surfaces up to the chord sag
// of kTessellationSegments segments per circle.
void tessellate(const AnalyticPrim& p, Mesh& mesh) {
  constexpr int n = kTessellationSegments;
  const auto onCircle = [&](int k, double radius, double y) {
    const double a = 2.0 * glm::pi<double>() * double(k % n) / double(n);
    return dvec3(p.centre.x + radius * std::cos(a), y, p.centre.z + radius * std::sin(a));
  };
  switch (p.kind) {
    case PrimKind::Floor: {
      const double e = p.extent, y = p.centre.y;
      const dvec3 c[4] = {{p.centre.x - e, y, p.centre.z - e}, {p.centre.x + e, y, p.centre.z - e},
                          {p.centre.x + e, y, p.centre.z + e}, {p.centre.x - e, y, p.centre.z + e}};
      if (p.radius <= 0.0) {
        mesh.quad(c[0], c[3], c[2], c[1]);
        return;
      }
      // A ring from the hole's rim out to the square: each rim segment joins the point where its
      // ray leaves the square (a square's boundary point per direction), and the square's corners
      // are covered by the segments around them.
      const auto toSquare = [&](int k) {
        const dvec3 r = onCircle(k, 1.0, y) - dvec3(p.centre.x, y, p.centre.z);
        const double s = e / std::max(std::abs(r.x), std::abs(r.z));
        return dvec3(p.centre.x + r.x * s, y, p.centre.z + r.z * s);
      };
      for (int k = 0; k < n; ++k) {
        mesh.quad(onCircle(k, p.radius, y), onCircle(k + 1, p.radius, y), toSquare(k + 1), toSquare(k));
        for (const dvec3& corner : c) {  // the corner between two segments' outer points
          const dvec3 a = toSquare(k) - p.centre, b = toSquare(k + 1) - p.centre, q = corner - p.centre;
          if (a.x * q.z - a.z * q.x > 0.0 && q.x * b.z - q.z * b.x > 0.0) {
            const uint32_t i0 = mesh.vertex(toSquare(k)), i1 = mesh.vertex(corner), i2 = mesh.vertex(toSquare(k + 1));
            mesh.triangle(i0, i1, i2);
          }
        }
      }
      return;
    }
    case PrimKind::Disc: {
      const uint32_t centre = mesh.vertex(p.centre);
      for (int k = 0; k < n; ++k)
        mesh.triangle(centre, mesh.vertex(onCircle(k + 1, p.radius, p.centre.y)), mesh.vertex(onCircle(k, p.radius, p.centre.y)));
      return;
    }
    case PrimKind::Cylinder:
      for (int k = 0; k < n; ++k)
        mesh.quad(onCircle(k, p.radius, p.centre.y), onCircle(k + 1, p.radius, p.centre.y),
                  onCircle(k + 1, p.radius, p.centre.y + p.extent), onCircle(k, p.radius, p.centre.y + p.extent));
      return;
    case PrimKind::Sphere: {
      constexpr int around = kSphereSegments, rings = kSphereSegments / 2;
      const auto at = [&](int ring, int k) {
        const double theta = glm::pi<double>() * double(ring) / double(rings);
        const double a = 2.0 * glm::pi<double>() * double(k % around) / double(around);
        return p.centre + p.radius * dvec3(std::sin(theta) * std::cos(a), std::cos(theta), std::sin(theta) * std::sin(a));
      };
      for (int ring = 0; ring < rings; ++ring)
        for (int k = 0; k < around; ++k) mesh.quad(at(ring, k), at(ring, k + 1), at(ring + 1, k + 1), at(ring + 1, k));
      return;
    }
  }
}

}  // namespace

CaptureGeometry RayScene::triangles() const {
  Mesh all;
  // Without Embree's padding float (commit()).
  all.vertices.assign(impl_->mesh.vertices.begin(), impl_->mesh.vertices.begin() + impl_->mesh.vertices.size() / 3 * 3);
  all.indices = impl_->mesh.indices;
  for (const auto& p : impl_->prims) tessellate(p, all);
  CaptureGeometry g;
  g.positions = std::move(all.vertices);
  g.indices = std::move(all.indices);
  return g;
}

RayScene::~RayScene() = default;

const SceneInfo& RayScene::info() const { return impl_->info; }
size_t RayScene::triangleCount() const { return impl_->mesh.triangleCount(); }
glm::dvec3 RayScene::meshMax() const { return impl_->meshMax; }

std::optional<SurfaceHit> RayScene::intersect(const dvec3& origin, const dvec3& direction, double tnear,
                                              double tfar) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh;
  std::memset(&rh, 0, sizeof(rh));
  rh.ray.org_x = static_cast<float>(origin.x);
  rh.ray.org_y = static_cast<float>(origin.y);
  rh.ray.org_z = static_cast<float>(origin.z);
  rh.ray.dir_x = static_cast<float>(direction.x);
  rh.ray.dir_y = static_cast<float>(direction.y);
  rh.ray.dir_z = static_cast<float>(direction.z);
  rh.ray.tnear = static_cast<float>(tnear);
  rh.ray.tfar = static_cast<float>(tfar);
  rh.ray.mask = 0xffffffffu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &ctx, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  return impl_->refine(rh.hit.geomID, rh.hit.primID, rh.ray.tfar, origin, direction);
}

int RayScene::countUnoccluded(const dvec3& origin, const dvec3* directions, int count, double tfar) const {
  int open = 0;
  const float ox = static_cast<float>(origin.x), oy = static_cast<float>(origin.y), oz = static_cast<float>(origin.z);
  const float tf = static_cast<float>(tfar);
  for (int base = 0; base < count; base += 16) {
    const int n = std::min(16, count - base);
    alignas(64) RTCRay16 rays;
    alignas(64) int valid[16];
    for (int k = 0; k < 16; ++k) {
      const bool on = k < n;
      const dvec3 d = on ? directions[base + k] : dvec3(0.0, 1.0, 0.0);
      valid[k] = on ? -1 : 0;
      rays.org_x[k] = ox;
      rays.org_y[k] = oy;
      rays.org_z[k] = oz;
      rays.dir_x[k] = static_cast<float>(d.x);
      rays.dir_y[k] = static_cast<float>(d.y);
      rays.dir_z[k] = static_cast<float>(d.z);
      rays.tnear[k] = 0.0f;
      rays.tfar[k] = tf;
      rays.time[k] = 0.0f;
      rays.mask[k] = 0xffffffffu;
      rays.id[k] = static_cast<unsigned>(k);
      rays.flags[k] = 0;
    }
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    rtcOccluded16(valid, impl_->scene, &ctx, &rays);
    for (int k = 0; k < n; ++k) open += rays.tfar[k] >= 0.0f;
  }
  return open;
}

}  // namespace aor::gen
