#pragma once
// The generated `aoreplay.glsl` of one pass of a user technique: its workgroup size, the `frame`
// and `params` uniform blocks, a sampler per read and an image per write, in the binding order the
// replay binds them (`aoreplay technique-header FILE.json PASS` prints it). The C++ side of the
// `frame` block is here too, so the two cannot disagree.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "techniques/user/user_technique_spec.h"

namespace aor {

// std140 layout of `frame`; every member sits where std140 puts it without padding of its own.
struct UserFrameBlock {
  glm::mat4 view{1.0f}, projection{1.0f}, invProjection{1.0f}, prevViewProjection{1.0f};
  glm::vec2 size{0.0f}, invSize{0.0f};
  uint32_t frameIndex = 0, historyValid = 0;
  float radius = 1.0f;
  uint32_t pad = 0;
};
static_assert(sizeof(UserFrameBlock) == 288, "std140 layout of the frame block");

// One binding of a pass, in set 0 order: frame, params (when there are parameters), the reads, the writes.
struct UserBinding {
  enum class Kind { Frame, Params, Read, Write } kind;
  std::string image;  // Read / Write: the image's name
};
std::vector<UserBinding> userPassBindings(const UserTechniqueSpec& spec, const UserPass& pass);

// The header's text for `pass`.
std::string userPassHeader(const UserTechniqueSpec& spec, const UserPass& pass);

// `params` as std140 bytes: one 4-byte member per parameter in the file's order (float as float,
// everything else as int), rounded up to 16 bytes.
std::vector<uint32_t> userParamsBlock(const UserTechniqueSpec& spec, const std::vector<double>& values);

}  // namespace aor
