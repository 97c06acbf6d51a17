#pragma once
// What a compute shader's SPIR-V says about its interface, read with SPIRV-Cross (as zeux's niagara
// reads its shaders): the descriptor type of each binding of set 0, its workgroup size and the size
// of its push-constant block. Pipelines are built from this, never from hand-typed lists.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace aor {

struct ShaderBinding {
  VkDescriptorType type = VK_DESCRIPTOR_TYPE_MAX_ENUM;
  bool arrayed = false;  // an image2DArray / sampler2DArray: bound through a 2D-array view
  std::string name;      // the variable's name in the shader, for error messages
};

struct ShaderInterface {
  std::vector<ShaderBinding> bindings;  // set 0, binding i; bindings are dense from 0
  uint32_t localSize[3] = {1, 1, 1};  // the defaults where a dimension is a specialisation constant
  int localSizeSpecId[3] = {-1, -1, -1};  // constant_id of each dimension given by one, else -1
  uint32_t pushConstantBytes = 0;
  uint64_t workgroupMemoryBytes = 0;  // its `shared` variables, at their natural sizes
  // The counting build's AoOpCounts buffer (shaders/counting/count_ops.glsl), set apart from
  // `bindings`: its binding number, or -1 in an ordinary build.
  int opCounterBinding = -1;
};

// Throws std::runtime_error naming `shaderName` when the module is not a compute shader aoreplay can
// bind (a set other than 0, a gap in the bindings, descriptor arrays). A workgroup size taken
// from specialisation constants is reported with their ids and defaults.
ShaderInterface reflectComputeShader(std::span<const uint32_t> spirv, const std::string& shaderName);

const char* descriptorTypeName(VkDescriptorType type);

}  // namespace aor
