#include "embedded_shaders.h"

#include <stdexcept>
#include <string>

namespace aor::spirv {

std::span<const uint32_t> code(std::string_view name, std::span<const EmbeddedShader> index) {
  for (const auto& shader : index)
    if (shader.name == name) return shader.code;
  throw std::logic_error("no embedded shader named '" + std::string(name) + "'");
}

}  // namespace aor::spirv
