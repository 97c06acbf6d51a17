#pragma once
// SPIR-V of every shader in this folder, compiled by glslang at build time (see CMakeLists.txt).
#include <cstddef>
#include <cstdint>
#include <span>

namespace aor::spirv {
#define AOR_DECLARE_SHADER(name)              \
  extern const uint32_t name[];               \
  extern const size_t name##_words;           \
  inline std::span<const uint32_t> name##_code() { return {name, name##_words}; }
AOR_DECLARE_SHADER(linearize_depth)
AOR_DECLARE_SHADER(reconstruct_normals)
AOR_DECLARE_SHADER(gtao)
AOR_DECLARE_SHADER(gtao_reference)
AOR_DECLARE_SHADER(spatial_columns_rgba16f)
AOR_DECLARE_SHADER(spatial_columns_r16f)
AOR_DECLARE_SHADER(spatial_denoise_rgba16f)
AOR_DECLARE_SHADER(spatial_denoise_r16f)
AOR_DECLARE_SHADER(temporal_denoise_rgba16f)
AOR_DECLARE_SHADER(temporal_denoise_r16f)
#undef AOR_DECLARE_SHADER
}  // namespace aor::spirv
