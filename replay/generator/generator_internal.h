#pragma once
// Internals of the synthetic capture generator, exposed for tests (tests/generator) and for tools
// that want to trace the same scenes. Everything here is deterministic: no global state, results
// depend only on the arguments (never on the thread count).
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "capture/capture.h"
#include "generator/generator.h"

namespace aor::gen {

inline constexpr double kNearPlane = 0.05;
// Segments around a circle when the analytic primitives are written as triangles: the chord's sag is
// r * (1 - cos(pi / 256)) = 7.5e-5 r, below the reference's self-intersection offset at 1 m.
inline constexpr int kTessellationSegments = 256;
// The sphere's segments around (and half as many rings): a sag of 5.4e-4 r, and 9216 triangles
// instead of 65536 (the OBJ is shipped with every sphere capture).
inline constexpr int kSphereSegments = 96;
inline constexpr double kFarPlane = 200.0;
// The sentence stored as scene.reference in capture.json.
inline constexpr const char* kReferenceDescription =
    "fraction of cosine-weighted hemisphere directions around the geometric normal that are "
    "unoccluded within distance R";

// /usr/share/glmark2/models/bunny.obj (Debian package glmark2-data).
std::filesystem::path defaultBunnyPath();

// Per-scene constants: default AO radius, the closed-form oracle (if any) and camera-path anchors.
// Azimuths are in degrees around +Y, measured from +X towards +Z (90 = camera on the +Z side).
struct SceneInfo {
  std::string name;
  double defaultRadius = 1.0;
  std::string oracle;             // human-readable closed form, "" when none
  glm::dvec3 focus{0.0};          // orbit / dolly target
  double distance = 5.0;          // horizontal orbit distance from the focus
  double height = 2.0;            // absolute camera height (world y) for orbit/dolly/static/cut
  double frontAzimuth = 90.0;     // centre of the 60 degree orbit arc
  double dollyEnd = 0.5;          // dolly ends at this fraction of the start offset
  glm::dvec3 cutEye{0.0}, cutTarget{0.0};        // second viewpoint of the "cut" path
  glm::dvec3 strafeEye{0.0}, strafeTarget{0.0};  // centre of the strafe and what it looks at
  double strafeSpan = 2.0;        // total sideways travel of "strafe" (world units)
};

// A ray hit refined in double precision. normal: unit geometric normal facing the ray origin.
struct SurfaceHit {
  double t = 0.0;
  glm::dvec3 position{0.0};
  glm::dvec3 normal{0.0};
};

// One scene traced with Embree 3: triangle meshes plus exact analytic primitives (floor plane with
// optional circular hole, disc, open cylinder, sphere) as Embree user geometry. Thread-safe for
// concurrent queries after construction. Throws aor::InputError for unknown names or a missing
// bunny model.
class RayScene {
 public:
  explicit RayScene(const std::string& name, const std::filesystem::path& bunnyObj = defaultBunnyPath());
  ~RayScene();
  RayScene(const RayScene&) = delete;
  RayScene& operator=(const RayScene&) = delete;

  const SceneInfo& info() const;
  size_t triangleCount() const;
  // Upper bound of the triangle meshes (excluding the analytic floor); for tests.
  glm::dvec3 meshMax() const;
  // The scene as world-space triangles, for the capture's geometry (format 1.1): the meshes as
  // they are and the analytic primitives tessellated (kTessellationSegments around each circle).
  CaptureGeometry triangles() const;

  // Closest hit with t in [tnear, tfar]; direction need not be normalised (t is in its units).
  std::optional<SurfaceHit> intersect(const glm::dvec3& origin, const glm::dvec3& direction,
                                      double tnear, double tfar) const;
  // Number of the `count` rays from one origin that are unoccluded (no hit with t in [0, tfar]),
  // traced as Embree ray packets.
  int countUnoccluded(const glm::dvec3& origin, const glm::dvec3* directions, int count, double tfar) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// ---- Reference AO ---------------------------------------------------------------------------
// First two dimensions of the Sobol sequence, in [0,1).
glm::dvec2 sobol2(uint32_t index);
// Per-pixel key for the Cranley-Patterson rotation: a hash of (x, y, frame, seed).
uint64_t pixelSampleKey(int x, int y, int frame, uint64_t seed);
// Fraction of `spp` cosine-weighted directions around unit normal `n` whose rays from
// p + n*epsilon reach distance `radius` unoccluded. Sobol points rotated by a key-derived offset.
double referenceVisibility(const RayScene& scene, const glm::dvec3& p, const glm::dvec3& n,
                           double radius, int spp, uint64_t sampleKey, double epsilon);
// Self-intersection offset for a point seen at `distance` from the camera.
double surfaceEpsilon(double distance);

// ---- Cameras --------------------------------------------------------------------------------
struct FrameCamera {
  glm::mat4 view{1.0f};
  glm::mat4 projection{1.0f};
  bool cut = false;
};
// Vulkan-ready projection (y flipped: view +Y -> NDC -y), depth [0,1] standard or reversed,
// finite (far = kFarPlane) or infinite far, near = kNearPlane.
glm::mat4 makeProjection(double verticalFovDegrees, double aspect, bool reversedZ, bool infiniteFar);
// Right-handed look-at (camera looks down -Z, +Y up), computed in double.
glm::mat4 makeView(const glm::dvec3& eye, const glm::dvec3& target, const glm::dvec3& up = {0, 1, 0});
std::vector<FrameCamera> cameraPath(const SceneInfo& scene, const GeneratorOptions& options);

// ---- Rendering ------------------------------------------------------------------------------
struct RenderSettings {
  int width = 64;
  int height = 36;
  int referenceSpp = 0;
  double radius = 1.0;
  bool reversedZ = false;
  bool writeNormals = true;
  bool depth2 = false;            // also write the second layer (GeneratorOptions::depth2)
  double depth2Separation = 0.01;
  uint64_t seed = 1;
  int threads = 0;  // 0: std::thread::hardware_concurrency()
};
// World-space ray through the centre of pixel (x, y) (row 0 at the top), starting on the near
// plane. Returns origin (camera position) and unit direction; tnear is the near-plane distance.
struct PixelRay {
  glm::dvec3 origin{0.0};
  glm::dvec3 direction{0.0};
  double tnear = 0.0;
};
PixelRay pixelRay(const glm::mat4& view, const glm::mat4& projection, bool reversedZ, int x, int y,
                  int width, int height);
// G-buffer (+ reference when referenceSpp > 0) of one frame. Sky (and geometry beyond a finite far
// plane): depth 1 (standard) / 0 (reversed), normal (0,0,0), visibility 1. With settings.depth2
// also `depth2`: the first hit at least depth2Separation beyond layer 0's along the same ray (sky
// where there is none, or no layer 0).
CaptureFrameData renderFrame(const RayScene& scene, const FrameCamera& camera,
                             const RenderSettings& settings, int frameIndex);

// ---- Options / metadata ---------------------------------------------------------------------
void validateOptions(const GeneratorOptions& options);
SceneInfo sceneInfo(const std::string& name);  // throws InputError for unknown names
nlohmann::json sceneMetadata(const SceneInfo& scene, const GeneratorOptions& options, double radius);

}  // namespace aor::gen
