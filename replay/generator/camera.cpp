// Projection, view and the deterministic camera paths of the generator.
#include <algorithm>
#include <cmath>

#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include "generator/generator_internal.h"

namespace aor::gen {
namespace {

using glm::dvec3;

constexpr double kPi = 3.14159265358979323846;
double radians(double degrees) { return degrees * kPi / 180.0; }

// Fraction i/(n-1) in [0,1]; 0 for a single frame.
double progress(int i, int n) { return n > 1 ? static_cast<double>(i) / (n - 1) : 0.0; }

dvec3 orbitEye(const SceneInfo& s, double azimuthDegrees) {
  const double a = radians(azimuthDegrees);
  return {s.focus.x + s.distance * std::cos(a), s.height, s.focus.z + s.distance * std::sin(a)};
}

// `eye` rotated about the vertical axis through `centre`.
dvec3 rotateAboutY(const dvec3& eye, const dvec3& centre, double degrees) {
  const double a = radians(degrees), c = std::cos(a), s = std::sin(a);
  const dvec3 r = eye - centre;
  return centre + dvec3(c * r.x - s * r.z, r.y, s * r.x + c * r.z);
}

}  // namespace

std::vector<std::string> pathNames() { return {"orbit", "dolly", "static", "cut", "strafe"}; }

glm::mat4 makeProjection(double verticalFovDegrees, double aspect, bool reversedZ, bool infiniteFar) {
  const double n = kNearPlane, f = kFarPlane;
  const double t = std::tan(radians(verticalFovDegrees) / 2.0);
  // clip.w = -z_view; depth = clip.z / clip.w = (A z + B) / (-z).
  double A = 0.0, B = 0.0;
  if (!reversedZ && !infiniteFar) {  // == glm::perspectiveRH_ZO
    A = f / (n - f);
    B = -(f * n) / (f - n);
  } else if (!reversedZ) {  // depth = 1 - n/d
    A = -1.0;
    B = -n;
  } else if (!infiniteFar) {  // depth = 1 - standard
    A = n / (f - n);
    B = f * n / (f - n);
  } else {  // depth = n/d
    A = 0.0;
    B = n;
  }
  glm::dmat4 P(0.0);
  P[0][0] = 1.0 / (aspect * t);
  P[1][1] = -1.0 / t;  // Vulkan: view +Y -> NDC -y (top of the image)
  P[2][2] = A;
  P[2][3] = -1.0;
  P[3][2] = B;
  return glm::mat4(P);
}

glm::mat4 makeView(const dvec3& eye, const dvec3& target, const dvec3& up) {
  return glm::mat4(glm::lookAtRH(eye, target, up));
}

std::vector<FrameCamera> cameraPath(const SceneInfo& s, const GeneratorOptions& o) {
  const int n = std::max(o.frames, 0);
  const glm::mat4 proj = makeProjection(o.verticalFovDegrees, static_cast<double>(o.width) / o.height,
                                        o.reversedZ, o.infiniteFar);
  std::vector<FrameCamera> frames(n);
  const int cutAt = n >= 2 ? n / 2 : -1;
  for (int i = 0; i < n; ++i) {
    FrameCamera& fc = frames[i];
    fc.projection = proj;
    const double u = progress(i, n);
    dvec3 eye, target = s.focus;
    if (o.path == "orbit") {
      eye = orbitEye(s, s.frontAzimuth - 30.0 + 60.0 * u);
    } else if (o.path == "dolly") {
      const dvec3 start = orbitEye(s, s.frontAzimuth);
      eye = s.focus + (start - s.focus) * (1.0 - (1.0 - s.dollyEnd) * u);
    } else if (o.path == "static") {
      eye = orbitEye(s, s.frontAzimuth);
    } else if (o.path == "cut") {
      if (cutAt < 0 || i < cutAt) {
        eye = orbitEye(s, s.frontAzimuth - 5.0 + 10.0 * progress(i, std::max(cutAt, 1)));
      } else {
        eye = rotateAboutY(s.cutEye, s.cutTarget, -1.5 + 3.0 * progress(i - cutAt, n - cutAt));
        target = s.cutTarget;
        fc.cut = (i == cutAt);
      }
    } else {  // strafe: constant orientation, sideways translation
      const dvec3 forward = glm::normalize(s.strafeTarget - s.strafeEye);
      const dvec3 right = glm::normalize(glm::cross(forward, dvec3(0, 1, 0)));
      const dvec3 offset = right * (s.strafeSpan * (u - 0.5));
      eye = s.strafeEye + offset;
      target = s.strafeTarget + offset;
    }
    fc.view = makeView(eye, target);
  }
  return frames;
}

}  // namespace aor::gen
