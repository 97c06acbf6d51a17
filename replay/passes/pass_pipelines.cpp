#include <fmt/format.h>

#include "embedded_shaders.h"
#include "gtao.h"
#include "linearize_depth.h"
#include "passes/passes.h"
#include "reconstruct_normals.h"
#include "spatial_denoise.h"
#include "temporal_denoise.h"
#include "vk/context.h"

namespace aor {
namespace {
constexpr VkDescriptorType kSampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
constexpr VkDescriptorType kStorage = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;

SpecializationValue spec(int id, int value) { return {uint32_t(id), uint32_t(value)}; }
SpecializationValue spec(int id, bool on) { return {uint32_t(id), on ? 1u : 0u}; }
}  // namespace

PassPipelines::~PassPipelines() {
  for (auto& [key, p] : pipelines_) destroyPipeline(vk_, p);
}

const ComputePipeline& PassPipelines::get(const std::string& key, std::span<const uint32_t> code,
                                          std::span<const VkDescriptorType> bindings, uint32_t pushConstantSize,
                                          uint32_t workgroupSize, std::span<const SpecializationValue> specialization) {
  auto [it, fresh] = pipelines_.try_emplace(key);
  if (fresh) {
    it->second = createComputePipeline(vk_, code, bindings, pushConstantSize, specialization);
    it->second.workgroupSize = workgroupSize;
  }
  return it->second;
}

VkFormat aoFormat(bool bent) { return bent ? VK_FORMAT_R16G16B16A16_SFLOAT : VK_FORMAT_R16_SFLOAT; }

const ComputePipeline& PassPipelines::linearizeDepth() {
  VkDescriptorType bindings[] = {kStorage, kStorage};  // depth read as a storage image
  return get("linearize", spirv::linearize_depth_code(), bindings, sizeof(shader::LinearizeConstants),
             shader::kLinearizeWorkgroupSize);
}

const ComputePipeline& PassPipelines::reconstructNormals() {
  VkDescriptorType bindings[] = {kSampled, kStorage};
  return get("normals", spirv::reconstruct_normals_code(), bindings, sizeof(shader::ReconstructNormalsConstants),
             shader::kWorkgroupSize);
}

const ComputePipeline& PassPipelines::gtao(int slices, int steps, bool bent, bool viewSpaceNormals, bool thin,
                                           bool halfResolution) {
  VkDescriptorType bindings[] = {kStorage, kStorage, kStorage};  // distance and normals read as storage images
  SpecializationValue values[] = {spec(shader::kGtaoSpecSlices, slices), spec(shader::kGtaoSpecSteps, steps),
                                  spec(shader::kGtaoSpecBent, bent), spec(shader::kGtaoSpecViewNormals, viewSpaceNormals),
                                  spec(shader::kGtaoSpecThin, thin), spec(shader::kGtaoSpecHalfResolution, halfResolution)};
  return get(fmt::format("gtao:{}:{}:{}:{}:{}:{}", slices, steps, bent, viewSpaceNormals, thin, halfResolution),
             spirv::gtao_code(), bindings, sizeof(shader::GtaoConstants), shader::kGtaoWorkgroupSize, values);
}

const ComputePipeline& PassPipelines::gtaoReference(int slices, bool bent, bool viewSpaceNormals, bool thin) {
  VkDescriptorType bindings[] = {kSampled, kSampled, kStorage};
  SpecializationValue values[] = {spec(shader::kGtaoSpecSlices, slices), spec(shader::kGtaoSpecBent, bent),
                                  spec(shader::kGtaoSpecViewNormals, viewSpaceNormals), spec(shader::kGtaoSpecThin, thin)};
  return get(fmt::format("gtao_reference:{}:{}:{}:{}", slices, bent, viewSpaceNormals, thin), spirv::gtao_reference_code(),
             bindings, sizeof(shader::GtaoConstants), shader::kWorkgroupSize, values);
}

// The AO images' format is fixed in each SPIR-V (lavapipe cannot read storage images without a
// format), hence one module per aoFormat(bent).
const ComputePipeline& PassPipelines::spatialColumns(bool bent, bool halfResolution) {
  VkDescriptorType bindings[] = {kStorage, kStorage, kStorage, kStorage};
  SpecializationValue values[] = {spec(shader::kSpatialSpecHalfResolution, halfResolution)};
  auto code = bent ? spirv::spatial_columns_rgba16f_code() : spirv::spatial_columns_r16f_code();
  return get(fmt::format("spatial_columns:{}:{}", bent, halfResolution), code, bindings, sizeof(shader::SpatialConstants),
             shader::kSpatialColumnsWorkgroupSize, values);
}

const ComputePipeline& PassPipelines::spatial(bool bent) {
  VkDescriptorType bindings[] = {kStorage, kStorage, kStorage, kStorage};
  SpecializationValue values[] = {spec(shader::kSpatialSpecBent, bent)};
  auto code = bent ? spirv::spatial_denoise_rgba16f_code() : spirv::spatial_denoise_r16f_code();
  return get(fmt::format("spatial:{}", bent), code, bindings, sizeof(shader::SpatialConstants), shader::kWorkgroupSize, values);
}

const ComputePipeline& PassPipelines::temporal(bool bent, bool hasHistory, bool halfResolution) {
  VkDescriptorType bindings[] = {kStorage, kStorage, kStorage, kStorage, kStorage};
  SpecializationValue values[] = {spec(shader::kTemporalSpecBent, bent), spec(shader::kTemporalSpecHistory, hasHistory),
                                  spec(shader::kTemporalSpecHalfResolution, halfResolution)};
  auto code = bent ? spirv::temporal_denoise_rgba16f_code() : spirv::temporal_denoise_r16f_code();
  return get(fmt::format("temporal:{}:{}:{}", bent, hasHistory, halfResolution), code, bindings,
             sizeof(shader::TemporalConstants), shader::kWorkgroupSize, values);
}

}  // namespace aor
