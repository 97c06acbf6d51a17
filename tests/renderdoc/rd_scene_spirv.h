#pragma once
// SPIR-V of shaders/scene.vert and shaders/scene.frag, compiled and embedded at build time.
#include <cstddef>
#include <cstdint>

namespace aor::spirv {
extern const uint32_t scene_vert[];
extern const size_t scene_vert_words;
extern const uint32_t scene_vert_stripped[];  // the same without OpName / OpMemberName (spirv-opt --strip-debug)
extern const size_t scene_vert_stripped_words;
extern const uint32_t scene_frag[];
extern const size_t scene_frag_words;
}  // namespace aor::spirv
