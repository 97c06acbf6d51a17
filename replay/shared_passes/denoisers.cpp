// Passes 2 and 3 of seed 000 as blocks: the spatial bilateral blur, and the temporal reprojection
// with history (or, without history, the upsample of half-resolution AO).
#include "shared_passes/shared_passes.h"
#include "blocks/spatial_denoise.h"
#include "blocks/temporal_denoise.h"
#include "runtime/pass_context.h"

namespace aor::shared_passes {
namespace {

constexpr const char* kAoHistory = "ao_history";

// The AO images' format is fixed in each SPIR-V (lavapipe cannot read storage images without a
// format), hence one module per aoImageFormat(bent).
std::string formatSuffix(bool bent) { return bent ? "rgba16f" : "r16f"; }

struct TemporalTarget {
  graph::ResourceId current, distance, historyAo, historyDistance, target;
};

// The temporal shader as `temporal` (blending history when there is some) or as `upsample`.
graph::ResourceId addTemporalShaderPass(const char* name, FrameBuilder& frame, const DenoiseInput& in,
                                        const TemporalTarget& t) {
  bool hasHistory = t.historyAo != graph::kNoResource && t.historyDistance != graph::kNoResource;
  const auto& cam = frame.camera();
  const auto& prev = hasHistory ? frame.previousCamera() : cam;
  auto constants = shader::temporalReprojection(cam.view, cam.projection, prev.view, prev.projection, cam.width, cam.height);
  constants.blend = frame.settings().f(kTemporalKey);
  // Without history the shader variant never reads bindings 2-3; the current AO and distance (of
  // the formats those bindings declare) stand in so every binding is valid and no pass declares a
  // read of a history image that does not exist.
  graph::ResourceId historyAo = hasHistory ? t.historyAo : t.current;
  graph::ResourceId historyDistance = hasHistory ? t.historyDistance : t.distance;
  std::string shader = "blocks/temporal_denoise_" + formatSuffix(in.bent);
  SpecializationValue values[] = {specializationValue(shader::kTemporalSpecBent, in.bent), specializationValue(shader::kTemporalSpecHistory, hasHistory),
                                  specializationValue(shader::kTemporalSpecHalfResolution, in.divisor == 2)};
  std::vector<SpecializationValue> specialization(std::begin(values), std::end(values));
  auto& pipelines = frame.pipelines();
  frame.graph().addPass(
      name,
      [&](graph::PassBuilder& b) {
        b.read(t.current, graph::Access::StorageRead);
        b.read(t.distance, graph::Access::StorageRead);
        if (hasHistory) {
          b.read(t.historyAo, graph::Access::StorageRead);
          b.read(t.historyDistance, graph::Access::StorageRead);
        }
        b.write(t.target);
      },
      [&pipelines, shader, specialization, constants, t, historyAo, historyDistance](graph::PassContext& ctx) {
        dispatchCompute(ctx, pipelines.get(shader, specialization), {t.current, t.distance, historyAo, historyDistance, t.target},
                        &constants, uint32_t(constants.size.x), uint32_t(constants.size.y));
      });
  return t.target;
}

}  // namespace

Parameter spatialParameter() {
  Parameter p = boolParameter(kSpatialKey, true, "seed 000's 5x5 spatial bilateral denoise 0/1");
  p.shared = true;
  return p;
}

Parameter temporalParameter(double defaultWeight) {
  Parameter p = floatParameter(kTemporalKey, defaultWeight, 0, 0.98, "seed 000's temporal history weight, 0 = no temporal pass");
  p.shared = true;
  return p;
}

HistoryNeeds temporalDenoiseHistory(const Settings& settings) {
  float weight = settings.f(kTemporalKey);
  bool keeps = weight > 0.0f;
  return {keeps, keeps, keeps ? "" : "temporal=0", weight};
}

std::optional<Settings> withoutTemporalDenoise(const Settings& settings) {
  Settings without = settings;
  without.set(kTemporalKey, 0);
  return without;
}

VkFormat aoImageFormat(bool bent) { return bent ? VK_FORMAT_R16G16B16A16_SFLOAT : VK_FORMAT_R16_SFLOAT; }

graph::ResourceId addSpatialDenoise(FrameBuilder& frame, const DenoiseInput& in) {
  shader::SpatialConstants constants{};
  const auto& aoDesc = frame.graph().resources().at(in.ao).desc;
  constants.size = {int(aoDesc.width), int(aoDesc.height)};
  uint32_t w = aoDesc.width, h = aoDesc.height;
  auto& g = frame.graph();
  auto columnSum = g.createImage("ao_column_sum", {w, h, aoImageFormat(in.bent)});
  auto columnWeightAndEdge = g.createImage("ao_column_weight_edge", {w, h, VK_FORMAT_R16G16_SFLOAT});
  auto blurred = g.createImage("ao_blurred", {w, h, aoImageFormat(in.bent)});
  auto distance = frame.linearDistance();
  auto ao = in.ao;
  auto& pipelines = frame.pipelines();
  std::string suffix = formatSuffix(in.bent);
  std::vector<SpecializationValue> columns{specializationValue(shader::kSpatialSpecHalfResolution, in.divisor == 2)};
  std::vector<SpecializationValue> rows{specializationValue(shader::kSpatialSpecBent, in.bent)};
  // The 5x5 blur in two dispatches, vertical legs then rows (why: shaders/blocks/spatial_denoise.h).
  // A spatial_columns thread sums a strip of kSpatialStrip pixels of one column.
  g.addPass(
      "spatial_columns",
      [&](graph::PassBuilder& b) {
        b.read(ao, graph::Access::StorageRead);
        b.read(distance, graph::Access::StorageRead);
        b.write(columnSum);
        b.write(columnWeightAndEdge);
      },
      [&pipelines, suffix, columns, constants, ao, distance, columnSum, columnWeightAndEdge](graph::PassContext& ctx) {
        uint32_t strips = (uint32_t(constants.size.y) + shader::kSpatialStrip - 1) / shader::kSpatialStrip;
        dispatchCompute(ctx, pipelines.get("blocks/spatial_columns_" + suffix, columns), {ao, distance, columnSum, columnWeightAndEdge},
                        &constants, uint32_t(constants.size.x), strips);
      });
  g.addPass(
      "spatial",
      [&](graph::PassBuilder& b) {
        b.read(ao, graph::Access::StorageRead);
        b.read(columnSum, graph::Access::StorageRead);
        b.read(columnWeightAndEdge, graph::Access::StorageRead);
        b.write(blurred);
      },
      [&pipelines, suffix, rows, constants, ao, columnSum, columnWeightAndEdge, blurred](graph::PassContext& ctx) {
        dispatchCompute(ctx, pipelines.get("blocks/spatial_denoise_" + suffix, rows), {ao, columnSum, columnWeightAndEdge, blurred},
                        &constants, uint32_t(constants.size.x), uint32_t(constants.size.y));
      });
  if (!frame.settings().b(kSpatialKey)) {
    frame.explain("spatial", "spatial=0");
    frame.explain("spatial_columns", "spatial=0");
    return in.ao;
  }
  return blurred;
}

graph::ResourceId addTemporalDenoise(FrameBuilder& frame, const DenoiseInput& in) {
  auto& g = frame.graph();
  uint32_t w = frame.size().x, h = frame.size().y;
  auto distance = frame.linearDistance();
  if (frame.historyWanted()) {
    auto history = frame.history(kAoHistory, {w, h, aoImageFormat(in.bent)});
    return addTemporalShaderPass("temporal", frame, in,
                                 {in.ao, distance, history.previous, frame.previousDistance(), history.current});
  }
  // Declared anyway so the compiled graph shows it culled, with the reason.
  auto filtered = g.createImage("ao_filtered", {w, h, aoImageFormat(in.bent)});
  addTemporalShaderPass("temporal", frame, in, {in.ao, distance, graph::kNoResource, graph::kNoResource, filtered});
  frame.explain("temporal", frame.settings().f(kTemporalKey) <= 0.0f ? "temporal=0" : "single-frame replay: no history");
  if (in.divisor == 1) return in.ao;
  // Half-resolution AO still has to reach the frame's size; the temporal pass does it otherwise.
  auto upsampled = g.createImage("ao_upsampled", {w, h, aoImageFormat(in.bent)});
  return addTemporalShaderPass("upsample", frame, in, {in.ao, distance, graph::kNoResource, graph::kNoResource, upsampled});
}

}  // namespace aor::shared_passes
