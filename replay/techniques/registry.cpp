#include "techniques/registry.h"

#include <fmt/format.h>

#include "core/input_error.h"
#include "techniques/user/user_technique.h"

namespace aor {
namespace {

std::vector<const Technique*>& registry() {
  static std::vector<const Technique*> all = [] {
    std::vector<const Technique*> list;
#define AOR_DECLARE_TECHNIQUE(name) list.push_back(&name##Technique());
#include "techniques/builtin_techniques.inc"
#undef AOR_DECLARE_TECHNIQUE
    return list;
  }();
  return all;
}

}  // namespace

std::vector<const Technique*> userTechniques() {
  std::vector<const Technique*> out;
  for (const auto* t : registry())
    if (!t->testOnly) out.push_back(t);
  return out;
}

const Technique& findTechnique(std::string_view name) {
  if (isTechniquePath(name)) return loadUserTechnique(std::string(name));
  for (const auto* t : registry())
    if (t->name == name) return *t;
  std::vector<std::string> names;
  for (const auto* t : userTechniques()) names.push_back(t->name);
  throw InputError("", std::nullopt, "--technique", fmt::format("unknown technique '{}' ({})", name, fmt::join(names, ", ")));
}

void registerTechnique(const Technique* technique) {
  for (const auto* t : registry())
    if (t->name == technique->name) throw std::logic_error("technique '" + technique->name + "' registered twice");
  registry().push_back(technique);
}

const Technique& defaultTechnique() { return gtaoTechnique(); }

}  // namespace aor
