#pragma once
// The passes of the AO render graph. Each add*Pass declares its accesses in the graph's setup step
// and records its dispatch in the execute step; it returns the resource it writes.
#include <map>
#include <string>

#include <glm/glm.hpp>

#include "graph/render_graph.h"
#include "gtao.h"
#include "passes/camera.h"
#include "pipeline/settings.h"
#include "vk/resources.h"

namespace aor {

struct VulkanContext;

// Owns every compute pipeline; variants (specialisation constants) are created on first use.
class PassPipelines {
 public:
  explicit PassPipelines(VulkanContext& vk) : vk_(vk) {}
  ~PassPipelines();
  PassPipelines(const PassPipelines&) = delete;
  PassPipelines& operator=(const PassPipelines&) = delete;
  const ComputePipeline& linearizeDepth();
  const ComputePipeline& reconstructNormals();
  const ComputePipeline& gtao(int slices, int steps, bool bent, bool viewSpaceNormals, bool thin, bool halfResolution);
  const ComputePipeline& gtaoReference(int slices, bool bent, bool viewSpaceNormals, bool thin);
  const ComputePipeline& spatialColumns(bool bent, bool halfResolution);
  const ComputePipeline& spatial(bool bent);
  const ComputePipeline& temporal(bool bent, bool hasHistory, bool halfResolution);

 private:
  // The pipeline under `key`, created on first use.
  // `workgroupSize` is the shader's (its header's constant), for dispatchCompute's group count.
  const ComputePipeline& get(const std::string& key, std::span<const uint32_t> code,
                             std::span<const VkDescriptorType> bindings, uint32_t pushConstantSize,
                             uint32_t workgroupSize, std::span<const SpecializationValue> specialization = {});
  VulkanContext& vk_;
  std::map<std::string, ComputePipeline> pipelines_;
};

VkFormat aoFormat(bool bent);  // RGBA16F (bent.xyz, visibility) or R16F (visibility)

struct FrameCamera {
  glm::mat4 view{1.0f};
  glm::mat4 projection{1.0f};
  int width = 0, height = 0;
  uint32_t frameIndex = 0;
};
// GTAO and the spatial blur work on one texel per divisor x divisor pixels: 1, or 2 with half_res=1.
int aoResolutionDivisor(const AoSettings& settings);
// Size of the images they write: shader::reducedSize of the frame's by that divisor. The temporal
// pass (or `upsample`) brings the AO back to the frame's size.
glm::ivec2 aoWorkingSize(const FrameCamera& camera, const AoSettings& settings);

// Copies host staging buffers into the G-buffer images (normals may be kNoResource).
void addUploadPass(graph::RenderGraph& graph, const GpuBuffer& depth, graph::ResourceId depthImage,
                   const GpuBuffer* normals, graph::ResourceId normalsImage);
graph::ResourceId addLinearizeDepthPass(graph::RenderGraph& graph, PassPipelines& pipelines, const FrameCamera& camera,
                                        graph::ResourceId depth, graph::ResourceId distanceTarget);
graph::ResourceId addReconstructNormalsPass(graph::RenderGraph& graph, PassPipelines& pipelines,
                                            const FrameCamera& camera, graph::ResourceId distance);
struct GtaoInputs {
  graph::ResourceId distance;
  graph::ResourceId normals;
  bool viewSpaceNormals;  // reconstructed normals are view space; captured ones world space
};
// Push constants of the GTAO pass for a frame (shared with the CPU mirror).
shader::GtaoConstants gtaoConstants(const FrameCamera& camera, const AoSettings& settings);
graph::ResourceId addGtaoPass(graph::RenderGraph& graph, PassPipelines& pipelines, const FrameCamera& camera,
                              const AoSettings& settings, const GtaoInputs& inputs);
// The screen-space reference (`technique=reference`, shaders/gtao_reference.comp): the GTAO
// integral over kReferenceSlices noise-free slices and every pixel out to the radius. Writes the
// same image as addGtaoPass; spatial and temporal passes are not run after it.
inline constexpr int kReferenceSlices = 32;
graph::ResourceId addGtaoReferencePass(graph::RenderGraph& graph, PassPipelines& pipelines, const FrameCamera& camera,
                                       const AoSettings& settings, const GtaoInputs& inputs);
graph::ResourceId addSpatialPass(graph::RenderGraph& graph, PassPipelines& pipelines, const FrameCamera& camera,
                                 const AoSettings& settings, graph::ResourceId ao, graph::ResourceId distance);
struct TemporalInputs {
  graph::ResourceId current;           // this frame's denoised AO
  graph::ResourceId distance;          // this frame's linear distance
  graph::ResourceId historyAo;         // previous output, or kNoResource when history is invalid
  graph::ResourceId historyDistance;   // previous distance, or kNoResource
  graph::ResourceId target;            // history "current" image written here
  FrameCamera previousCamera;
};
graph::ResourceId addTemporalPass(graph::RenderGraph& graph, PassPipelines& pipelines, const FrameCamera& camera,
                                  const AoSettings& settings, const TemporalInputs& inputs);
// half_res=1 without a temporal pass: the temporal shader's upsample alone (no history), from the
// half-resolution `current` to the frame-sized `target`.
graph::ResourceId addUpsamplePass(graph::RenderGraph& graph, PassPipelines& pipelines, const FrameCamera& camera,
                                  const AoSettings& settings, graph::ResourceId current, graph::ResourceId distance,
                                  graph::ResourceId target);
// Copies `image` into a host-visible buffer; a root of the graph.
void addReadbackPass(graph::RenderGraph& graph, graph::ResourceId image, const GpuBuffer& target);
// Fills every channel of `image` with `value` (a side effect: never culled). Test-only fault
// injection, see ReplayOptions::testPoisonHistoryAt.
void addFillPass(graph::RenderGraph& graph, graph::ResourceId image, float value);

}  // namespace aor
