#pragma once
// Every compute pipeline of a replay, created the first time a pass records it (pipelines of culled
// passes are never made) and owned here, destroyed in one place. A pipeline is named by its shader
// and the values of its specialisation constants.
#include <map>
#include <span>
#include <string>
#include <vector>

#include "vk/resources.h"

namespace aor {

struct VulkanContext;

// A shader module to build pipelines from: its name (for errors and the cache key) and SPIR-V.
struct ShaderCode {
  std::string name;
  std::span<const uint32_t> code;
};

class PipelineCache {
 public:
  explicit PipelineCache(VulkanContext& vk) : vk_(vk) {}
  ~PipelineCache();
  PipelineCache(const PipelineCache&) = delete;
  PipelineCache& operator=(const PipelineCache&) = delete;

  const ComputePipeline& get(const ShaderCode& shader, std::span<const SpecializationValue> specialization = {});
  // An embedded shader (shaders/NAME.comp) by name.
  const ComputePipeline& get(const std::string& embeddedName, std::span<const SpecializationValue> specialization = {});
  size_t size() const { return pipelines_.size(); }

 private:
  VulkanContext& vk_;
  std::map<std::string, ComputePipeline> pipelines_;
};

}  // namespace aor
