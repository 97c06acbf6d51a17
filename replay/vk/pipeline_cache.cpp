#include "vk/pipeline_cache.h"

#include <fmt/format.h>

#include "embedded_shaders.h"
#include "vk/context.h"
#include "vk/op_counter.h"

namespace aor {

PipelineCache::~PipelineCache() {
  for (auto& [key, p] : pipelines_) destroyPipeline(vk_, p);
}

const ComputePipeline& PipelineCache::get(const ShaderCode& shader, std::span<const SpecializationValue> specialization) {
  std::string key = shader.name;
  for (const auto& s : specialization) key += fmt::format(":{}={}", s.id, s.value);
  auto [it, fresh] = pipelines_.try_emplace(key);
  if (fresh) {
    try {
      it->second = createComputePipeline(vk_, shader.code, shader.name, specialization);
    } catch (...) {
      pipelines_.erase(it);
      throw;
    }
  }
  return it->second;
}

const ComputePipeline& PipelineCache::get(const std::string& embeddedName, std::span<const SpecializationValue> specialization) {
  // While a replay counts (vk/op_counter.h), every embedded shader is its counting build.
  std::string name = vk_.opCounter ? embeddedName + std::string(kCountingBuildSuffix) : embeddedName;
  return get(ShaderCode{name, spirv::code(name)}, specialization);
}

}  // namespace aor
