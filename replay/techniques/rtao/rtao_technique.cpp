// Seed 003: ray-traced AO from the G-buffer, accumulated over frames (the nvpro-samples Vulkan
// ray-tracing tutorial's "G-Buffer and Ambient Occlusion" extension), as a technique module. Its
// rays traverse a BVH of the capture's geometry (format 1.1) in a compute shader, so it runs on
// every Vulkan device, or, where the device has ray queries, acceleration structures of the same
// triangles with the same rays. Seed 003 point by point: README.md in this folder.
#include <chrono>
#include <cstring>
#include <map>

#include <fmt/format.h>

#include "shared_passes/shared_passes.h"
#include "shared_passes/camera.h"
#include "capture/capture.h"
#include "core/input_error.h"
#include "runtime/pass_context.h"
#include "technique_api/frame_builder.h"
#include "technique_api/key_table.h"
#include "techniques/registry.h"
#include "techniques/rtao/rtao_accel.h"
#include "techniques/rtao/rtao_bvh.h"
#include "vk/context.h"
#include "vk/resources.h"
#include "vk/vk_check.h"

namespace aor {
namespace {

constexpr const char* kAccumulate = "accumulate";
constexpr const char* kMean = "rtao_mean";
constexpr const char* kSamplesValue = "accumulated_spp";

enum class Traversal { Auto, Compute, RayQuery };

struct RtaoSettings {
  float radius = 2.0f;
  int samples = 4;
  float power = 2.0f;
  bool distanceBased = true;
  bool accumulate = true;
  int maxFrames = 0;
  Traversal traversal = Traversal::Auto;
  float normalOffset = 1e-4f;
};

// Every key with its RtaoSettings field; defaults are the struct's.
const KeyTable<RtaoSettings>& keyTable() {
  using R = RtaoSettings;
  static const KeyTable<R> table = {
      radiusKey(&R::radius),
      intKey(&R::samples, "samples", 1, 1024, "rays per pixel per frame (AoControl::rtao_samples)"),
      floatKey(&R::power, "power", 0.0, 16.0, "exponent of each frame's visibility (AoControl::rtao_power; 1 = none)"),
      boolKey(&R::distanceBased, "distance_based",
              "1: a hit occludes by 1 - t/radius (closest hit); 0: any hit within the radius occludes fully "
              "(the reference's definition)"),
      boolKey(&R::accumulate, kAccumulate,
              "running mean over frames, restarted on any camera change, a cut, a size or settings change"),
      intKey(&R::maxFrames, "max_frames", 0, 1000000, "frames a mean accumulates at most, then it is kept (0 = no cap)"),
      enumKey(&R::traversal, "traversal", {"auto", "compute", "rayquery"},
              "ray traversal: compute (a compute-shader BVH, every device), rayquery (acceleration structures "
              "and ray queries; exit 3 on a device without VK_KHR_ray_query and VK_KHR_acceleration_structure), "
              "auto (rayquery where the device has both, else compute)"),
      floatKey(&R::normalOffset, "normal_offset", 0.0, 0.1,
               "ray origins move this many world units per unit of view distance (at least 1) along the normal "
               "before OffsetRay: the depth buffer's position is only within its precision of the surface"),
  };
  return table;
}

RtaoSettings rtaoSettings(const Settings& settings) { return keyTable().read(settings); }
const std::vector<std::string> kRayQueryExtensions = {kRayQueryExtension, kAccelerationStructureExtension};

// What the rays traverse: the BVH on the device (or only its sizes, for `aoreplay graph`), or the
// ray-query path's acceleration structures; and the accumulation's length at each frame replayed so
// far, for the next frame's weight and the report.
struct RtaoState : TechniqueState {
  VulkanContext* vk = nullptr;
  bool rayQuery = false;
  GpuBuffer nodes, triangles;
  uint64_t nodeBytes = 0, triangleBytes = 0;
  size_t nodeCount = 0, triangleCount = 0;
  uint32_t depth = 0;
  RtaoAccel accel;
  uint64_t graphTlasBytes = 0;  // without a device: the BLAS's input, standing in for the TLAS in `aoreplay graph`
  double buildMs = 0;
  std::map<uint32_t, uint32_t> accumulatedFrames;  // capture frame index -> frames in its mean

  ~RtaoState() override {
    if (!vk) return;
    destroyBuffer(*vk, nodes);
    destroyBuffer(*vk, triangles);
    if (rayQuery) destroyRtaoAccel(*vk, accel);
  }
  std::vector<std::pair<std::string, double>> reportValues() const override {
    if (rayQuery)
      return {{"rayquery", 1.0},
              {"as_triangles", double(accel.triangleCount)},
              {"as_blas_bytes", double(accel.blasBytes)},
              {"as_tlas_bytes", double(accel.tlasBytes)},
              {"as_bytes", double(accel.bytes())},
              {"as_build_bytes", double(accel.buildBytes)},
              {"as_build_ms", buildMs}};
    return {{"rayquery", 0.0},
            {"bvh_nodes", double(nodeCount)},
            {"bvh_triangles", double(triangleCount)},
            {"bvh_depth", double(depth)},
            {"bvh_bytes", double(nodeBytes + triangleBytes)},
            {"bvh_build_ms", buildMs}};
  }
};

// A device-local storage buffer holding `bytes`, filled through a staging copy that has finished
// when this returns (the graph imports it as last written by that transfer).
GpuBuffer uploadStorageBuffer(VulkanContext& vk, const void* data, uint64_t bytes) {
  GpuBuffer staging = createHostBuffer(vk, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  std::memcpy(staging.mapped, data, bytes);
  GpuBuffer buffer = createDeviceBuffer(vk, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  runOneTimeCommands(vk, [&](VkCommandBuffer cmd) {
    VkBufferCopy region{0, 0, bytes};
    vkCmdCopyBuffer(cmd, staging.buffer, buffer.buffer, 1, &region);
  });
  destroyBuffer(vk, staging);
  return buffer;
}

constexpr graph::ResourceState kUploaded{VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED};
constexpr graph::ResourceState kBuilt{VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                                   VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR, VK_IMAGE_LAYOUT_UNDEFINED};

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// Whether the rays are traced with ray queries: asked for, or `auto` on a context that enabled them
// (a run asks for them where the device offers them: rtaoDeviceExtensions). Without a device
// (`aoreplay graph`) only an explicit rayquery does.
bool usesRayQuery(const Settings& settings, const VulkanContext* vk) {
  switch (rtaoSettings(settings).traversal) {
    case Traversal::RayQuery: return true;
    case Traversal::Compute: return false;
    case Traversal::Auto: return vk && vk->enabled(kRayQueryExtension) && vk->enabled(kAccelerationStructureExtension);
  }
  return false;
}

// The compute path's BVH: built on the CPU (the build time is Embree's and the flattening), then
// uploaded once.
void prepareBvh(RtaoState& state, const CaptureGeometry& geometry, VulkanContext* vk) {
  auto start = std::chrono::steady_clock::now();
  RtaoBvh bvh = buildRtaoBvh(geometry);
  state.buildMs = msSince(start);
  state.nodeCount = bvh.nodes.size();
  state.triangleCount = bvh.triangles.size();
  state.depth = bvh.depth;
  state.nodeBytes = bvh.nodes.size() * sizeof(bvh.nodes[0]);
  state.triangleBytes = bvh.triangles.size() * sizeof(bvh.triangles[0]);
  if (vk) {
    state.nodes = uploadStorageBuffer(*vk, bvh.nodes.data(), state.nodeBytes);
    state.triangles = uploadStorageBuffer(*vk, bvh.triangles.data(), state.triangleBytes);
  }
}

// The ray-query path's BLAS and TLAS, built on the device (the build time is the inputs' upload and
// the device's builds, to their end).
void prepareAccel(RtaoState& state, const CaptureGeometry& geometry, VulkanContext* vk) {
  if (!vk) {
    state.graphTlasBytes = geometry.positions.size() * sizeof(float) + rtaoKeptTriangles(geometry).size() * 3 * sizeof(uint32_t);
    return;
  }
  for (const auto& e : kRayQueryExtensions)
    if (!vk->enabled(e))
      throw NoDeviceError(fmt::format("traversal=rayquery: device '{}' offers {} but this context did not enable it (the "
                                      "device lacks one of the features rayQuery, accelerationStructure, "
                                      "bufferDeviceAddress, or the command does not enable optional extensions)",
                                      vk->info.name, e));
  auto start = std::chrono::steady_clock::now();
  state.accel = buildRtaoAccel(*vk, geometry);
  state.buildMs = msSince(start);
}

std::unique_ptr<TechniqueState> prepareRtao(const ReplaySetup& setup) {
  auto state = std::make_unique<RtaoState>();
  CaptureGeometry geometry = loadGeometry(setup.capture);  // InputError naming the OBJ's line
  state->rayQuery = usesRayQuery(setup.settings, setup.vk);
  if (state->rayQuery)
    prepareAccel(*state, geometry, setup.vk);
  else
    prepareBvh(*state, geometry, setup.vk);
  state->vk = setup.vk;
  return state;
}

void checkRtaoCapture(const Settings&, const Capture& capture) {
  if (!capture.geometry)
    throw InputError((capture.folder / "capture.json").string(), std::nullopt, "geometry",
                     "--technique rtao traces rays against the scene's triangles and this capture has none: it needs "
                     "format 1.1's \"geometry\" (an OBJ, captures/FORMAT.md; `aoreplay capture` writes one)");
}

std::vector<std::string> missingRtaoExtensions(const Settings& settings, const DeviceInfo& device) {
  if (rtaoSettings(settings).traversal != Traversal::RayQuery) return {};
  std::vector<std::string> missing;
  for (const auto& e : kRayQueryExtensions)
    if (!device.hasExtension(e)) missing.push_back(e);
  return missing;
}

// The ray-query path's extensions, for the context to enable where the device offers them, unless
// the settings rule that path out.
std::vector<std::string> rtaoDeviceExtensions(const Settings& settings, const DeviceInfo&) {
  if (rtaoSettings(settings).traversal == Traversal::Compute) return {};
  return kRayQueryExtensions;
}

// The seed's updateFrame: any change of the camera matrix (or of the projection, the seed's fov)
// restarts the accumulation, beyond the host's history rules (cut, size, settings, jumps).
bool sameCamera(const FrameCamera& a, const FrameCamera& b) {
  return std::memcmp(&a.view, &b.view, sizeof(a.view)) == 0 && std::memcmp(&a.projection, &b.projection, sizeof(a.projection)) == 0;
}

struct Accumulation {
  bool continues = false;  // last frame's mean is read
  uint32_t frames = 1;     // frames in this frame's mean
  bool hold = false;       // max_frames reached: the mean is kept as it is
};

Accumulation accumulationOf(FrameBuilder& frame, const Settings& settings, RtaoState& state) {
  Accumulation a;
  a.continues = rtaoSettings(settings).accumulate && frame.historyWanted() && frame.historyValid() &&
                sameCamera(frame.camera(), frame.previousCamera());
  if (a.continues) {
    auto previous = state.accumulatedFrames.find(frame.previousCamera().frameIndex);
    if (previous == state.accumulatedFrames.end()) throw std::logic_error("rtao: the previous frame's accumulation is unknown");
    uint32_t cap = uint32_t(rtaoSettings(settings).maxFrames);
    a.hold = cap > 0 && previous->second >= cap;
    a.frames = a.hold ? previous->second : previous->second + 1;
  }
  state.accumulatedFrames[frame.camera().frameIndex] = a.frames;
  return a;
}

shader::RtaoConstants traceConstants(const FrameBuilder& frame, const Settings& settings, const Accumulation& a) {
  const auto& cam = frame.camera();
  auto params = projectionParams(cam.projection, cam.width, cam.height);
  glm::mat4 viewToWorld = glm::inverse(cam.view);
  shader::RtaoConstants c{};
  c.viewToWorld0 = glm::vec4(viewToWorld[0][0], viewToWorld[1][0], viewToWorld[2][0], viewToWorld[3][0]);
  c.viewToWorld1 = glm::vec4(viewToWorld[0][1], viewToWorld[1][1], viewToWorld[2][1], viewToWorld[3][1]);
  c.viewToWorld2 = glm::vec4(viewToWorld[0][2], viewToWorld[1][2], viewToWorld[2][2], viewToWorld[3][2]);
  c.ndcToViewMul = params.ndcToViewMul;
  c.ndcToViewAdd = params.ndcToViewAdd;
  c.invSize = {1.0f / float(cam.width), 1.0f / float(cam.height)};
  c.size = {cam.width, cam.height};
  RtaoSettings r = rtaoSettings(settings);
  c.radius = r.radius;
  c.power = r.power;
  c.normalOffset = r.normalOffset;
  c.newWeight = 1.0f / float(a.frames);
  c.frameNumber = a.frames - 1;
  c.hold = a.hold ? 1u : 0u;
  return c;
}

// What the trace pass traverses, imported into the frame's graph: the BVH's two storage buffers, or
// the TLAS (which refers to the BLAS; both were built and waited for in prepare).
struct TraceScene {
  std::vector<graph::ResourceId> buffers;
  graph::Access access = graph::Access::StorageRead;
};

TraceScene importScene(graph::RenderGraph& g, const RtaoState& state) {
  auto importOne = [&](const char* name, uint64_t bytes, const GpuBuffer& buffer, const graph::ResourceState& after) {
    return state.vk ? g.importExternalBuffer(name, {bytes}, buffer, after) : g.importBuffer(name, {bytes});
  };
  if (state.rayQuery)
    return {{importOne("rtao_tlas", state.vk ? state.accel.tlasBytes : state.graphTlasBytes, state.accel.tlas, kBuilt)},
            graph::Access::AccelerationStructureRead};
  return {{importOne("bvh_nodes", state.nodeBytes, state.nodes, kUploaded),
           importOne("bvh_triangles", state.triangleBytes, state.triangles, kUploaded)},
          graph::Access::StorageRead};
}

void addRtaoPasses(FrameBuilder& frame, const Settings& settings) {
  auto& state = frame.state<RtaoState>();
  Accumulation a = accumulationOf(frame, settings, state);
  auto& g = frame.graph();
  TraceScene scene = importScene(g, state);
  auto size = frame.size();
  graph::ImageDesc meanDesc{size.x, size.y, VK_FORMAT_R32_SFLOAT};
  graph::ResourceId previous = graph::kNoResource, mean;
  if (frame.historyWanted()) {
    auto history = frame.history(kMean, meanDesc);
    mean = history.current;
    if (a.continues) previous = history.previous;
  } else {
    mean = g.createImage(kMean, meanDesc);
  }
  bool worldNormals = frame.worldNormals() != graph::kNoResource;
  graph::ResourceId normals = worldNormals ? frame.worldNormals() : frame.reconstructedNormals();
  graph::ResourceId distance = frame.linearDistance();
  RtaoSettings r = rtaoSettings(settings);
  std::vector<SpecializationValue> specialization{specializationValue(shader::kRtaoSpecSamples, r.samples),
                                                  specializationValue(shader::kRtaoSpecDistanceBased, r.distanceBased),
                                                  specializationValue(shader::kRtaoSpecWorldNormals, worldNormals)};
  shader::RtaoConstants c = traceConstants(frame, settings, a);
  // Bindings in the shader's order: distance, normals, the scene's buffers, last frame's mean, the mean.
  std::vector<Bind> bindings = {distance, normals};
  bindings.insert(bindings.end(), scene.buffers.begin(), scene.buffers.end());
  if (previous != graph::kNoResource) bindings.push_back(previous);
  bindings.push_back(mean);
  std::string shader = fmt::format("rtao/rtao_{}{}", previous != graph::kNoResource ? "accumulate" : "first",
                                   state.rayQuery ? "_rayquery" : "");
  auto& pipelines = frame.pipelines();
  g.addPass(
      "rtao",
      [&](graph::PassBuilder& b) {
        b.read(distance, graph::Access::StorageRead);
        b.read(normals, graph::Access::StorageRead);
        for (graph::ResourceId buffer : scene.buffers) b.read(buffer, scene.access);
        if (previous != graph::kNoResource) b.read(previous, graph::Access::StorageRead);
        b.write(mean);
      },
      [&pipelines, specialization, c, bindings, shader](graph::PassContext& ctx) {
        const ComputePipeline& pipeline = pipelines.get(shader, specialization);
        dispatchCompute(ctx, pipeline, bindings, &c, sizeof(c), groupsFor(pipeline, uint32_t(c.size.x), uint32_t(c.size.y)));
      });
  frame.reportValue("accumulated_frames", a.frames);
  frame.reportValue(kSamplesValue, double(a.frames) * r.samples);
  frame.setOutput(mean, OutputLayout::visibilityOnly());
}

HistoryNeeds rtaoHistory(const Settings& settings) {
  bool keeps = rtaoSettings(settings).accumulate;
  return {keeps, false, keeps ? "" : "accumulate=0"};
}

std::optional<Settings> rtaoWithoutAccumulation(const Settings& settings) {
  Settings without = settings;
  without.set(kAccumulate, 0);
  return without;
}

Technique makeRtao() {
  Technique t;
  t.name = "rtao";
  t.seed = "003 ray-traced AO from the G-buffer, accumulated over frames";
  t.summary = "cosine-weighted AO rays from the depth buffer's surfaces against the capture's geometry (a BVH "
              "traversed in a compute shader, or ray queries where the device has them), running mean over frames "
              "while the camera is still";
  t.parameters = keyTable().parameters();
  t.inputs.normals = InputUse::Optional;
  t.samplesValue = kSamplesValue;
  t.addPasses = addRtaoPasses;
  t.history = rtaoHistory;
  t.withoutHistory = rtaoWithoutAccumulation;
  t.checkCapture = checkRtaoCapture;
  t.missingDeviceExtensions = missingRtaoExtensions;
  t.deviceExtensions = rtaoDeviceExtensions;
  t.prepare = prepareRtao;
  return t;
}

}  // namespace

const Technique& rtaoTechnique() {
  static const Technique t = makeRtao();
  return t;
}

}  // namespace aor
