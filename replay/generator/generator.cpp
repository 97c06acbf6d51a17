// generateCapture: option checks, scene metadata, frame loop.
#include <algorithm>
#include <cmath>

#include "core/input_error.h"
#include "generator/generator_internal.h"
#include "core/output_directory.h"

namespace aor::gen {
namespace {

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

void fail(const std::string& field, const std::string& problem) {
  throw InputError("", std::nullopt, field, problem);
}

}  // namespace

void validateOptions(const GeneratorOptions& o) {
  (void)sceneInfo(o.scene);  // throws InputError "unknown scene ..." for names it does not know
  const auto paths = pathNames();
  if (std::find(paths.begin(), paths.end(), o.path) == paths.end())
    fail("path", "unknown camera path '" + o.path + "' (expected one of: " + joined(paths) + ")");
  constexpr int kMaxSize = 16384;
  if (o.width <= 0 || o.width > kMaxSize)
    fail("width", "must be in 1.." + std::to_string(kMaxSize) + ", got " + std::to_string(o.width));
  if (o.height <= 0 || o.height > kMaxSize)
    fail("height", "must be in 1.." + std::to_string(kMaxSize) + ", got " + std::to_string(o.height));
  if (o.frames <= 0 || o.frames > 100000)
    fail("frames", "must be in 1..100000, got " + std::to_string(o.frames));
  if (o.referenceSpp < 0 || o.referenceSpp > (1 << 20))
    fail("reference_spp", "must be in 0..1048576, got " + std::to_string(o.referenceSpp));
  if (o.radius && !(std::isfinite(*o.radius) && *o.radius > 0.0f))
    fail("radius", "AO radius must be a positive finite number of world units, got " + std::to_string(*o.radius));
  if (o.depth2 && !(std::isfinite(o.depth2Separation) && o.depth2Separation > 0.0 && o.depth2Separation <= 1000.0))
    fail("depth2_separation", "must be a positive finite number of world units up to 1000, got " + std::to_string(o.depth2Separation));
  if (!(o.verticalFovDegrees >= 0.5f && o.verticalFovDegrees <= 179.0f))
    fail("fov", "vertical field of view must be in [0.5, 179] degrees, got " + std::to_string(o.verticalFovDegrees));
}

nlohmann::json sceneMetadata(const SceneInfo& scene, const GeneratorOptions& o, double radius) {
  nlohmann::json options = {
      {"scene", o.scene},
      {"width", o.width},
      {"height", o.height},
      {"frames", o.frames},
      {"path", o.path},
      {"reference_spp", o.referenceSpp},
      {"radius", o.radius ? nlohmann::json(*o.radius) : nlohmann::json(nullptr)},
      {"reversed_z", o.reversedZ},
      {"infinite_far", o.infiniteFar},
      {"write_normals", o.writeNormals},
      {"vertical_fov_degrees", o.verticalFovDegrees},
      {"seed", o.seed},
  };
  // Only captures with a second layer name it, so every other capture's capture.json is unchanged.
  if (o.depth2) {
    options["depth2"] = true;
    options["depth2_separation"] = o.depth2Separation;
  }
  nlohmann::json generator = {
      {"tool", "aoreplay capture"},
      {"version", 1},
      {"options", options},
      {"near", kNearPlane},
      {"far", o.infiniteFar ? nlohmann::json(nullptr) : nlohmann::json(kFarPlane)},
      {"depth", o.reversedZ ? "reversed" : "standard"},
      {"geometry", "exact: Embree 3 triangles + analytic floor/disc/cylinder/sphere, geometric normals"},
      {"sampling",
       "cosine-weighted Sobol (0,2) points, per-pixel Cranley-Patterson rotation hashed from (x, y, frame, seed); "
       "rays from p + n*1e-4*max(1, camera distance), tfar = ao_radius, binary visibility"},
      {"sky", "depth = far value (1 standard, 0 reversed), normal (0,0,0), reference 1"},
      {"geometry_file",
       "scene.obj: the meshes' triangles as traced, the analytic primitives tessellated with " +
           std::to_string(kTessellationSegments) + " segments per circle, the sphere " + std::to_string(kSphereSegments) +
           " x " + std::to_string(kSphereSegments / 2) + " (the floor a 1e4 m square)"},
  };
  if (o.depth2)
    generator["depth2"] = "depth peeling along each pixel's ray: the first surface at least depth2_separation world units "
                          "beyond layer 0's hit (two-sided surfaces: a back face counts); sky where there is none";
  nlohmann::json j = {
      {"name", scene.name},
      {"ao_radius", radius},
      {"units", "meters"},
      {"up", {0, 1, 0}},
      {"path", o.path},
      {"generator", generator},
      {"reference", std::string(kReferenceDescription) + " (R = ao_radius)"},
      {"reference_spp", o.referenceSpp},
  };
  if (!scene.oracle.empty()) j["oracle"] = scene.oracle;
  return j;
}

void generateCapture(const GeneratorOptions& options, const std::filesystem::path& out) {
  validateOptions(options);
  // Checked and locked before the (long) ray tracing: a folder that may not be replaced, or one
  // another run is writing, is refused before any work.
  OutputDirectory folder(out, ResultKind::Capture);
  const RayScene scene(options.scene);
  const double radius = options.radius ? static_cast<double>(*options.radius) : scene.info().defaultRadius;
  const auto cameras = cameraPath(scene.info(), options);

  RenderSettings settings;
  settings.width = options.width;
  settings.height = options.height;
  settings.referenceSpp = options.referenceSpp;
  settings.radius = radius;
  settings.reversedZ = options.reversedZ;
  settings.writeNormals = options.writeNormals;
  settings.depth2 = options.depth2;
  settings.depth2Separation = options.depth2Separation;
  settings.seed = options.seed;

  std::vector<CaptureFrameData> frames;
  frames.reserve(cameras.size());
  const int total = static_cast<int>(cameras.size());
  for (int i = 0; i < total; ++i) {
    frames.push_back(renderFrame(scene, cameras[i], settings, i));
    if (options.progress) options.progress(i + 1, total);
  }
  const CaptureGeometry geometry = scene.triangles();
  writeCaptureFiles(folder.staging(), options.width, options.height, frames, sceneMetadata(scene.info(), options, radius),
                    &geometry);
  folder.commit();
}

}  // namespace aor::gen
