// Primary visibility (G-buffer) and the reference AO integrator.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <limits>
#include <mutex>
#include <optional>
#include <thread>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include "generator/generator_internal.h"

namespace aor::gen {
namespace {

using glm::dvec3;
using glm::dvec4;

constexpr double kTwoPi = 6.28318530717958647692;

uint64_t mix64(uint64_t z) {
  z += 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// Unprojects pixel centres of one camera; shared by pixelRay() and renderFrame().
struct RayGenerator {
  glm::dmat4 invView, invProj, viewProj;
  dvec3 eye;
  double nearDepth;
  int width, height;

  RayGenerator(const glm::mat4& view, const glm::mat4& projection, bool reversedZ, int w, int h)
      : width(w), height(h) {
    const glm::dmat4 V(view), P(projection);
    invView = glm::inverse(V);
    invProj = glm::inverse(P);
    viewProj = P * V;
    eye = dvec3(invView[3]);
    nearDepth = reversedZ ? 1.0 : 0.0;
  }

  PixelRay ray(int x, int y) const {
    const double nx = (2.0 * x + 1.0) / width - 1.0;
    const double ny = (2.0 * y + 1.0) / height - 1.0;
    dvec4 v = invProj * dvec4(nx, ny, nearDepth, 1.0);
    v /= v.w;  // view-space point on the near plane
    const dvec3 dirView(v);
    const dvec3 dirWorld = glm::dmat3(invView) * dirView;
    PixelRay r;
    r.origin = eye;
    r.tnear = glm::length(dirWorld);
    r.direction = dirWorld / r.tnear;
    return r;
  }

  double depth(const dvec3& p) const {
    const dvec4 clip = viewProj * dvec4(p, 1.0);
    return clip.z / clip.w;
  }
};

}  // namespace

glm::dvec2 sobol2(uint32_t index) {
  // Dimension 0: van der Corput (bit reversal); dimension 1: Sobol's second generator matrix.
  uint32_t r0 = index;
  r0 = (r0 << 16) | (r0 >> 16);
  r0 = ((r0 & 0x00ff00ffu) << 8) | ((r0 & 0xff00ff00u) >> 8);
  r0 = ((r0 & 0x0f0f0f0fu) << 4) | ((r0 & 0xf0f0f0f0u) >> 4);
  r0 = ((r0 & 0x33333333u) << 2) | ((r0 & 0xccccccccu) >> 2);
  r0 = ((r0 & 0x55555555u) << 1) | ((r0 & 0xaaaaaaaau) >> 1);
  uint32_t r1 = 0;
  for (uint32_t v = 1u << 31, i = index; i; i >>= 1, v ^= v >> 1)
    if (i & 1u) r1 ^= v;
  return {r0 * 0x1.0p-32, r1 * 0x1.0p-32};
}

uint64_t pixelSampleKey(int x, int y, int frame, uint64_t seed) {
  uint64_t h = mix64(seed ^ 0x414f5265706c6179ull);  // "AOReplay"
  h = mix64(h ^ static_cast<uint32_t>(x));
  h = mix64(h ^ static_cast<uint32_t>(y));
  return mix64(h ^ static_cast<uint32_t>(frame));
}

double surfaceEpsilon(double distance) { return 1e-4 * std::max(1.0, distance); }

double referenceVisibility(const RayScene& scene, const dvec3& p, const dvec3& n, double radius, int spp,
                           uint64_t sampleKey, double epsilon) {
  if (spp <= 0) return 1.0;
  // Cranley-Patterson rotation.
  const double rot0 = static_cast<double>(sampleKey & 0xffffffffu) * 0x1.0p-32;
  const double rot1 = static_cast<double>(sampleKey >> 32) * 0x1.0p-32;
  // Orthonormal basis around n (Duff et al. 2017).
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z);
  const double b = n.x * n.y * a;
  const dvec3 t(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
  const dvec3 bt(b, sign + n.y * n.y * a, -n.y);
  const dvec3 origin = p + n * epsilon;
  int open = 0;
  constexpr int kBatch = 64;
  dvec3 dirs[kBatch];
  for (int first = 0; first < spp; first += kBatch) {
    const int count = std::min(kBatch, spp - first);
    for (int k = 0; k < count; ++k) {
      const glm::dvec2 s = sobol2(static_cast<uint32_t>(first + k));
      double u0 = s.x + rot0, u1 = s.y + rot1;
      if (u0 >= 1.0) u0 -= 1.0;
      if (u1 >= 1.0) u1 -= 1.0;
      const double r = std::sqrt(u0), phi = kTwoPi * u1;
      const double z = std::sqrt(std::max(0.0, 1.0 - u0));
      dirs[k] = t * (r * std::cos(phi)) + bt * (r * std::sin(phi)) + n * z;
    }
    open += scene.countUnoccluded(origin, dirs, count, radius);
  }
  return static_cast<double>(open) / spp;
}

PixelRay pixelRay(const glm::mat4& view, const glm::mat4& projection, bool reversedZ, int x, int y, int width,
                  int height) {
  return RayGenerator(view, projection, reversedZ, width, height).ray(x, y);
}

CaptureFrameData renderFrame(const RayScene& scene, const FrameCamera& camera, const RenderSettings& s,
                             int frameIndex) {
  const int W = s.width, H = s.height;
  const size_t count = static_cast<size_t>(W) * H;
  CaptureFrameData out;
  out.view = camera.view;
  out.projection = camera.projection;
  out.cut = camera.cut;
  out.gbuffer.width = W;
  out.gbuffer.height = H;
  out.gbuffer.depth.assign(count, s.reversedZ ? 0.0f : 1.0f);
  if (s.writeNormals) out.gbuffer.normals.assign(count * 3, 0.0f);
  if (s.depth2) out.gbuffer.depth2.assign(count, s.reversedZ ? 0.0f : 1.0f);
  std::vector<float> reference;
  if (s.referenceSpp > 0) reference.assign(count, 1.0f);

  const RayGenerator gen(camera.view, camera.projection, s.reversedZ, W, H);
  // Depth as the attachment stores it, or nothing beyond a finite far plane (which a rasteriser
  // would clip: the cleared sky value stays).
  auto storedDepth = [&](const dvec3& position) -> std::optional<float> {
    const double depth = gen.depth(position);
    if (s.reversedZ ? !(depth >= 0.0) : !(depth <= 1.0)) return std::nullopt;
    return static_cast<float>(std::clamp(depth, 0.0, 1.0));
  };
  auto shadeRow = [&](int y) {
    for (int x = 0; x < W; ++x) {
      const size_t i = static_cast<size_t>(y) * W + x;
      const PixelRay ray = gen.ray(x, y);
      const auto hit = scene.intersect(ray.origin, ray.direction, ray.tnear, std::numeric_limits<double>::infinity());
      if (!hit) continue;
      const auto depth = storedDepth(hit->position);
      if (!depth) continue;
      out.gbuffer.depth[i] = *depth;
      if (s.depth2) {
        // Depth peeling along the same ray: the next surface at least the separation further on.
        // t is in world units (the direction is a unit vector).
        const auto second = scene.intersect(ray.origin, ray.direction, hit->t + s.depth2Separation,
                                            std::numeric_limits<double>::infinity());
        if (second) {
          if (const auto depth2 = storedDepth(second->position)) out.gbuffer.depth2[i] = *depth2;
        }
      }
      if (s.writeNormals) {
        out.gbuffer.normals[3 * i + 0] = static_cast<float>(hit->normal.x);
        out.gbuffer.normals[3 * i + 1] = static_cast<float>(hit->normal.y);
        out.gbuffer.normals[3 * i + 2] = static_cast<float>(hit->normal.z);
      }
      if (s.referenceSpp > 0) {
        reference[i] = static_cast<float>(referenceVisibility(scene, hit->position, hit->normal, s.radius,
                                                              s.referenceSpp,
                                                              pixelSampleKey(x, y, frameIndex, s.seed),
                                                              surfaceEpsilon(hit->t)));
      }
    }
  };

  int threads = s.threads > 0 ? s.threads : static_cast<int>(std::thread::hardware_concurrency());
  threads = std::clamp(threads, 1, std::max(1, H));
  std::atomic<int> nextRow{0};
  std::exception_ptr error;
  std::mutex errorMutex;
  auto worker = [&] {
    try {
      for (int y = nextRow++; y < H; y = nextRow++) shadeRow(y);
    } catch (...) {
      std::lock_guard lock(errorMutex);
      if (!error) error = std::current_exception();
      nextRow = H;
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);
  if (s.referenceSpp > 0) out.reference = std::move(reference);
  return out;
}

}  // namespace aor::gen
