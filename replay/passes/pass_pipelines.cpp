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
}  // namespace

PassPipelines::~PassPipelines() {
  for (auto& [key, p] : pipelines_) destroyPipeline(vk_, p);
}

VkFormat aoFormat(bool bent) { return bent ? VK_FORMAT_R16G16B16A16_SFLOAT : VK_FORMAT_R16_SFLOAT; }

const ComputePipeline& PassPipelines::linearizeDepth() {
  auto [it, fresh] = pipelines_.try_emplace("linearize");
  if (fresh) {
    VkDescriptorType bindings[] = {kStorage, kStorage};  // depth read as a storage image
    it->second = createComputePipeline(vk_, spirv::linearize_depth_code(), bindings, sizeof(shader::LinearizeConstants), {});
  }
  return it->second;
}

const ComputePipeline& PassPipelines::reconstructNormals() {
  auto [it, fresh] = pipelines_.try_emplace("normals");
  if (fresh) {
    VkDescriptorType bindings[] = {kSampled, kStorage};
    it->second = createComputePipeline(vk_, spirv::reconstruct_normals_code(), bindings,
                                       sizeof(shader::ReconstructNormalsConstants), {});
  }
  return it->second;
}

const ComputePipeline& PassPipelines::gtao(int slices, int steps, bool bent, bool viewSpaceNormals, bool thin) {
  auto [it, fresh] = pipelines_.try_emplace(fmt::format("gtao:{}:{}:{}:{}:{}", slices, steps, bent, viewSpaceNormals, thin));
  if (fresh) {
    VkDescriptorType bindings[] = {kStorage, kStorage, kStorage};  // distance and normals read as storage images
    SpecializationValue spec[] = {{uint32_t(shader::kGtaoSpecSlices), uint32_t(slices)},
                                  {uint32_t(shader::kGtaoSpecSteps), uint32_t(steps)},
                                  {uint32_t(shader::kGtaoSpecBent), bent ? 1u : 0u},
                                  {uint32_t(shader::kGtaoSpecViewNormals), viewSpaceNormals ? 1u : 0u},
                                  {uint32_t(shader::kGtaoSpecThin), thin ? 1u : 0u}};
    it->second = createComputePipeline(vk_, spirv::gtao_code(), bindings, sizeof(shader::GtaoConstants), spec);
  }
  return it->second;
}

const ComputePipeline& PassPipelines::gtaoReference(int slices, bool bent, bool viewSpaceNormals, bool thin) {
  auto [it, fresh] = pipelines_.try_emplace(fmt::format("gtao_reference:{}:{}:{}:{}", slices, bent, viewSpaceNormals, thin));
  if (fresh) {
    VkDescriptorType bindings[] = {kSampled, kSampled, kStorage};
    SpecializationValue spec[] = {{uint32_t(shader::kGtaoSpecSlices), uint32_t(slices)},
                                  {uint32_t(shader::kGtaoSpecBent), bent ? 1u : 0u},
                                  {uint32_t(shader::kGtaoSpecViewNormals), viewSpaceNormals ? 1u : 0u},
                                  {uint32_t(shader::kGtaoSpecThin), thin ? 1u : 0u}};
    it->second = createComputePipeline(vk_, spirv::gtao_reference_code(), bindings, sizeof(shader::GtaoConstants), spec);
  }
  return it->second;
}

const ComputePipeline& PassPipelines::spatialColumns(bool bent) {
  auto [it, fresh] = pipelines_.try_emplace(fmt::format("spatial_columns:{}", bent));
  if (fresh) {
    VkDescriptorType bindings[] = {kStorage, kStorage, kStorage, kStorage};  // every image a storage image
    auto code = bent ? spirv::spatial_columns_rgba16f_code() : spirv::spatial_columns_r16f_code();  // = aoFormat(bent)
    it->second = createComputePipeline(vk_, code, bindings, sizeof(shader::SpatialConstants), {});
  }
  return it->second;
}

const ComputePipeline& PassPipelines::spatial(bool bent) {
  auto [it, fresh] = pipelines_.try_emplace(fmt::format("spatial:{}", bent));
  if (fresh) {
    VkDescriptorType bindings[] = {kStorage, kStorage, kStorage, kStorage, kStorage};  // every image a storage image
    SpecializationValue spec[] = {{uint32_t(shader::kSpatialSpecBent), bent ? 1u : 0u}};
    auto code = bent ? spirv::spatial_denoise_rgba16f_code() : spirv::spatial_denoise_r16f_code();  // = aoFormat(bent)
    it->second = createComputePipeline(vk_, code, bindings, sizeof(shader::SpatialConstants), spec);
  }
  return it->second;
}

const ComputePipeline& PassPipelines::temporal(bool bent, bool hasHistory) {
  auto [it, fresh] = pipelines_.try_emplace(fmt::format("temporal:{}:{}", bent, hasHistory));
  if (fresh) {
    VkDescriptorType bindings[] = {kStorage, kStorage, kStorage, kStorage, kStorage};  // every image a storage image
    SpecializationValue spec[] = {{uint32_t(shader::kTemporalSpecBent), bent ? 1u : 0u},
                                  {uint32_t(shader::kTemporalSpecHistory), hasHistory ? 1u : 0u}};
    auto code = bent ? spirv::temporal_denoise_rgba16f_code() : spirv::temporal_denoise_r16f_code();  // = aoFormat(bent)
    it->second = createComputePipeline(vk_, code, bindings, sizeof(shader::TemporalConstants), spec);
  }
  return it->second;
}

}  // namespace aor
