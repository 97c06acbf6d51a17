#include "technique_api/technique.h"

#include <algorithm>

#include <fmt/format.h>

#include "technique_api/settings.h"

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

std::function<std::vector<std::string>(const DeviceInfo& device)> optionalExtensionsOf(std::vector<Settings> runs) {
  return [runs = std::move(runs)](const DeviceInfo& device) {
    std::vector<std::string> wanted;
    for (const auto& settings : runs) {
      const Technique& t = settings.technique();
      if (!t.deviceExtensions) continue;
      for (auto& e : t.deviceExtensions(settings, device))
        if (std::find(wanted.begin(), wanted.end(), e) == wanted.end()) wanted.push_back(std::move(e));
    }
    return wanted;
  };
}

}  // namespace aor
