#pragma once
// Compiles a user technique's pass to SPIR-V at run time with libshaderc: its shader, the pass's
// generated aoreplay.glsl (techniques/user/user_header.h) and the technique's own #includes
// (relative to its folder, the path rules of captures). The result is cached on disk under the
// SHA-256 of what produced it (compiler, options, header, sources); an entry is used only when that
// key and its includes match and its SPIR-V validates, else it is compiled anew and replaced. Every
// result is checked against the header's interface. A compile error is an InputError naming the
// shader's file and line.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "techniques/user/user_technique_spec.h"

namespace aor {

// "shaderc 2023.2, SPIR-V 1.6 rev 1": part of every cache key.
std::string shadercVersion();

// Where compiled shaders are kept: $AOREPLAY_SHADER_CACHE, else $XDG_CACHE_HOME/aoreplay/shaders,
// else ~/.cache/aoreplay/shaders; empty when none can be named (nothing is cached then).
std::filesystem::path userShaderCacheFolder();

struct CompiledUserShader {
  std::vector<uint32_t> spirv;
  bool fromCache = false;
};

// The SPIR-V of `spec.passes[passIndex]`. Throws InputError. `countingBuild`: the shader's counting
// build (vk/op_counter.h), the counting prelude appended to its generated header.
CompiledUserShader compileUserPass(const UserTechniqueSpec& spec, size_t passIndex, bool countingBuild = false);

}  // namespace aor
