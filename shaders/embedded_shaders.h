#pragma once
// SPIR-V of every shader under shaders/, compiled by glslang at build time and found by name: the
// path without ".comp" ("gtao/gtao"). See CMakeLists.txt.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

namespace aor::spirv {

struct EmbeddedShader {
  std::string_view name;
  std::span<const uint32_t> code;
};

std::span<const EmbeddedShader> aor_shaders();  // generated index of shaders/
// The shader called `name` in `index` (default: shaders/); throws std::logic_error naming it when
// there is none.
std::span<const uint32_t> code(std::string_view name, std::span<const EmbeddedShader> index = aor_shaders());
// The text of shaders/counting/count_ops.glsl, which the counting build inserts into every shader.
std::string_view countOpsPrelude();

}  // namespace aor::spirv
