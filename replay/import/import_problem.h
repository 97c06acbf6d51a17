#pragma once
// A problem with what a RenderDoc capture holds, found while turning it into a capture frame. The
// import adds the file and frame and reports it as an InputError (exit 2).
#include <stdexcept>
#include <string>

namespace aor {

struct ImportProblem : std::runtime_error {
  ImportProblem(std::string field, const std::string& problem) : std::runtime_error(problem), field(std::move(field)) {}
  std::string field;  // the option it concerns (--view, --normals, ...), empty when none
};

}  // namespace aor
