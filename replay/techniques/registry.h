#pragma once
// The one list of techniques: the built-ins (registry.cpp, one line each) and those tests register.
#include <string_view>
#include <vector>

#include "technique_api/technique.h"

namespace aor {

// Every technique a user can name, in registration order.
std::vector<const Technique*> userTechniques();
// By name: a built-in, or one a test registered; a value containing '/' or ending in ".json" is a
// user technique's technique.json (techniques/user/user_technique.h), loaded on first use. Throws
// InputError (field --technique) listing the user techniques, or naming the file and key.
const Technique& findTechnique(std::string_view name);
// --technique's default where a command has one: seed 000's GTAO.
const Technique& defaultTechnique();
// Tests only: adds a technique (testOnly ones are never listed to users). The pointer must outlive
// the program's use of it.
void registerTechnique(const Technique* technique);

// Each built-in's definition, in its folder (replay/techniques/NAME/).
#define AOR_DECLARE_TECHNIQUE(name) const Technique& name##Technique();
#include "techniques/builtin_techniques.inc"
#undef AOR_DECLARE_TECHNIQUE

}  // namespace aor
