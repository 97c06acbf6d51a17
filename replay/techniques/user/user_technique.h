#pragma once
// A user's technique (`--technique PATH`, user_techniques/FORMAT.md) as a Technique like the built-ins:
// its technique.json read and checked, every pass compiled (shader_compiler.h), then registered
// under its name for the rest of the process, so that the run, sweep, graph, ao_bench and the
// report treat it as any other.
#include <string>
#include <string_view>

#include "technique_api/technique.h"

namespace aor {

// A --technique value naming a file: it contains '/' or ends in ".json".
bool isTechniquePath(std::string_view value);

// The technique of the file at `path`, loaded once per file. Throws InputError naming the file
// and the key (exit 2).
const Technique& loadUserTechnique(const std::string& path);

// `aoreplay technique-header FILE.json PASS`: the pass's generated aoreplay.glsl. Throws InputError.
std::string userTechniqueHeader(const std::string& path, const std::string& pass);

}  // namespace aor
