#include "vk/shader_reflection.h"

#include <map>
#include <memory>
#include <stdexcept>
#include <string_view>

#include <fmt/format.h>
#include <spirv_cross/spirv_cross_c.h>

namespace aor {
namespace {

struct ContextDeleter {
  void operator()(spvc_context_s* c) const { spvc_context_destroy(c); }
};

struct ResourceKind {
  spvc_resource_type type;
  VkDescriptorType descriptor;
};
constexpr ResourceKind kResourceKinds[] = {
    {SPVC_RESOURCE_TYPE_UNIFORM_BUFFER, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
    {SPVC_RESOURCE_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
    {SPVC_RESOURCE_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
    {SPVC_RESOURCE_TYPE_SAMPLED_IMAGE, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
    {SPVC_RESOURCE_TYPE_SEPARATE_IMAGE, VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE},
    {SPVC_RESOURCE_TYPE_ACCELERATION_STRUCTURE, VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR},
};

// Bytes of the module's Workgroup variables (GLSL `shared`), each the sum of its members' natural
// sizes: SPIRV-Cross's C interface lists no such variables, and the walk over the module's type
// declarations is short. Drivers may pad; this is the least a device must hold.
uint64_t workgroupMemoryBytes(std::span<const uint32_t> spirv) {
  constexpr uint32_t kTypeBool = 20, kTypeInt = 21, kTypeFloat = 22, kTypeVector = 23, kTypeMatrix = 24, kTypeArray = 28,
                     kTypeStruct = 30, kTypePointer = 32, kConstant = 43, kVariable = 59, kWorkgroup = 4;
  std::map<uint32_t, uint64_t> size, constant, pointee;
  uint64_t total = 0;
  for (size_t at = 5; at < spirv.size();) {
    const uint32_t op = spirv[at] & 0xffff, words = spirv[at] >> 16;
    if (words == 0 || at + words > spirv.size()) break;
    const uint32_t* w = &spirv[at];
    auto sizeOf = [&](uint32_t id) { return size.count(id) ? size[id] : 0; };
    if (op == kTypeBool) size[w[1]] = 4;
    if ((op == kTypeInt || op == kTypeFloat) && words >= 3) size[w[1]] = w[2] / 8;
    if ((op == kTypeVector || op == kTypeMatrix) && words >= 4) size[w[1]] = sizeOf(w[2]) * w[3];
    if (op == kTypeArray && words >= 4) size[w[1]] = sizeOf(w[2]) * (constant.count(w[3]) ? constant[w[3]] : 0);
    if (op == kTypeStruct)
      for (uint32_t m = 2; m < words; ++m) size[w[1]] += sizeOf(w[m]);
    if (op == kConstant && words >= 4) constant[w[2]] = w[3];
    if (op == kTypePointer && words >= 4 && w[2] == kWorkgroup) pointee[w[1]] = sizeOf(w[3]);
    if (op == kVariable && words >= 4 && w[3] == kWorkgroup) total += pointee.count(w[1]) ? pointee[w[1]] : 0;
    at += words;
  }
  return total;
}

}  // namespace

const char* descriptorTypeName(VkDescriptorType type) {
  switch (type) {
    case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER: return "uniform buffer";
    case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER: return "storage buffer";
    case VK_DESCRIPTOR_TYPE_STORAGE_IMAGE: return "storage image";
    case VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER: return "sampler";
    case VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE: return "sampled image";
    case VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR: return "acceleration structure";
    default: return "unknown descriptor";
  }
}

ShaderInterface reflectComputeShader(std::span<const uint32_t> spirv, const std::string& shaderName) {
  auto fail = [&](const std::string& why) { return std::runtime_error(fmt::format("shader {}: {}", shaderName, why)); };
  spvc_context raw = nullptr;
  if (spvc_context_create(&raw) != SPVC_SUCCESS) throw fail("cannot create a SPIRV-Cross context");
  std::unique_ptr<spvc_context_s, ContextDeleter> context(raw);
  spvc_parsed_ir ir = nullptr;
  spvc_compiler compiler = nullptr;
  spvc_resources resources = nullptr;
  if (spvc_context_parse_spirv(raw, spirv.data(), spirv.size(), &ir) != SPVC_SUCCESS ||
      spvc_context_create_compiler(raw, SPVC_BACKEND_NONE, ir, SPVC_CAPTURE_MODE_TAKE_OWNERSHIP, &compiler) != SPVC_SUCCESS ||
      spvc_compiler_create_shader_resources(compiler, &resources) != SPVC_SUCCESS)
    throw fail(fmt::format("not readable SPIR-V ({})", spvc_context_get_last_error_string(raw)));
  if (spvc_compiler_get_execution_model(compiler) != SpvExecutionModelGLCompute) throw fail("not a compute shader");

  ShaderInterface out;
  for (const auto& kind : kResourceKinds) {
    const spvc_reflected_resource* list = nullptr;
    size_t count = 0;
    spvc_resources_get_resource_list_for_type(resources, kind.type, &list, &count);
    for (size_t i = 0; i < count; ++i) {
      const auto& r = list[i];
      unsigned set = spvc_compiler_get_decoration(compiler, r.id, SpvDecorationDescriptorSet);
      unsigned binding = spvc_compiler_get_decoration(compiler, r.id, SpvDecorationBinding);
      spvc_type type = spvc_compiler_get_type_handle(compiler, r.type_id);
      if (kind.type == SPVC_RESOURCE_TYPE_STORAGE_BUFFER && std::string_view(spvc_compiler_get_name(compiler, r.base_type_id)) == "AoOpCounts") {
        out.opCounterBinding = int(binding);
        continue;
      }
      if (set != 0) throw fail(fmt::format("'{}' is in descriptor set {}; only set 0 is bound", r.name, set));
      if (spvc_type_get_num_array_dimensions(type) != 0) throw fail(fmt::format("'{}' is a descriptor array", r.name));
      if (binding >= out.bindings.size()) out.bindings.resize(binding + 1);
      if (out.bindings[binding].type != VK_DESCRIPTOR_TYPE_MAX_ENUM)
        throw fail(fmt::format("bindings '{}' and '{}' share binding {}", out.bindings[binding].name, r.name, binding));
      bool image = kind.type == SPVC_RESOURCE_TYPE_STORAGE_IMAGE || kind.type == SPVC_RESOURCE_TYPE_SAMPLED_IMAGE ||
                   kind.type == SPVC_RESOURCE_TYPE_SEPARATE_IMAGE;
      out.bindings[binding] = {kind.descriptor, image && spvc_type_get_image_arrayed(type), r.name};
    }
  }
  for (size_t b = 0; b < out.bindings.size(); ++b)
    if (out.bindings[b].type == VK_DESCRIPTOR_TYPE_MAX_ENUM) throw fail(fmt::format("binding {} is missing (bindings must be dense)", b));

  const spvc_reflected_resource* push = nullptr;
  size_t pushCount = 0;
  spvc_resources_get_resource_list_for_type(resources, SPVC_RESOURCE_TYPE_PUSH_CONSTANT, &push, &pushCount);
  if (pushCount > 0) {
    size_t bytes = 0;
    spvc_compiler_get_declared_struct_size(compiler, spvc_compiler_get_type_handle(compiler, push[0].base_type_id), &bytes);
    out.pushConstantBytes = uint32_t(bytes);
  }
  for (unsigned d = 0; d < 3; ++d)
    out.localSize[d] = spvc_compiler_get_execution_mode_argument_by_index(compiler, SpvExecutionModeLocalSize, d);
  spvc_specialization_constant dims[3] = {};
  spvc_compiler_get_work_group_size_specialization_constants(compiler, &dims[0], &dims[1], &dims[2]);
  for (unsigned d = 0; d < 3; ++d) {
    if (!dims[d].id) continue;
    out.localSizeSpecId[d] = int(dims[d].constant_id);
    out.localSize[d] = spvc_constant_get_scalar_u32(spvc_compiler_get_constant_handle(compiler, dims[d].id), 0, 0);
  }
  out.workgroupMemoryBytes = workgroupMemoryBytes(spirv);
  return out;
}

}  // namespace aor
