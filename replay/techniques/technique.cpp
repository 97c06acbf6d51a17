#include "techniques/technique.h"

#include <fmt/format.h>

namespace aor {

const Parameter* Technique::parameter(std::string_view key) const {
  for (const auto& p : parameters)
    if (p.key == key) return &p;
  return nullptr;
}

const Preset* Technique::preset(std::string_view presetName) const {
  for (const auto& p : presets)
    if (p.name == presetName) return &p;
  return nullptr;
}

const DebugView* Technique::debugView(std::string_view viewName) const {
  for (const auto& v : debugViews)
    if (v.name == viewName) return &v;
  return nullptr;
}

std::string Technique::keyList() const {
  std::vector<std::string> keys;
  for (const auto& p : parameters) keys.push_back(p.key);
  return keys.empty() ? "(none)" : fmt::format("{}", fmt::join(keys, ", "));
}

std::string Technique::tunableKeyList() const {
  std::vector<std::string> keys;
  for (const auto& p : parameters)
    if (p.tunable) keys.push_back(p.key);
  return keys.empty() ? "(none)" : fmt::format("{}", fmt::join(keys, ", "));
}

std::string Technique::presetList() const {
  std::vector<std::string> names;
  for (const auto& p : presets) names.push_back(p.name);
  return names.empty() ? "(none)" : fmt::format("{}", fmt::join(names, ", "));
}

}  // namespace aor
