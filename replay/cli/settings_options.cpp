#include "cli/settings_options.h"

#include "options/frame_range.h"

#include <charconv>
#include <cstring>

#include <fmt/format.h>

#include "techniques/registry.h"

namespace aor::cli {

std::string keyTable(const Technique& t) {
  size_t width = 0;
  for (const auto& p : t.parameters) width = std::max(width, p.key.size());
  std::string out;
  for (const auto& p : t.parameters)
    out += fmt::format("  {:<{}}  {}{}: {}\n", p.key, width, describeRange(p), p.tunable ? ", tunable" : "", p.doc);
  return out.empty() ? "  (none)\n" : out;
}

std::string presetTable(const Technique& t) {
  if (t.presets.empty()) return "(none: it runs with its defaults)";
  std::vector<std::string> items;
  for (const auto& p : t.presets) {
    std::vector<std::string> values;
    for (const auto& [key, value] : p.values) values.push_back(fmt::format("{}={}", key, valueText(*t.parameter(key), value)));
    items.push_back(fmt::format("{} ({}{})", p.name, fmt::join(values, " "), p.name == t.defaultPreset ? "; default" : ""));
  }
  return fmt::format("{}", fmt::join(items, ", "));
}

const Technique& techniqueForHelp(int argc, const char* const* argv, const Technique& fallback) {
  for (int i = 1; i < argc; ++i) {
    std::string_view arg = argv[i];
    std::string_view name;
    if (arg == "--technique" && i + 1 < argc) name = argv[i + 1];
    else if (arg.rfind("--technique=", 0) == 0) name = arg.substr(std::strlen("--technique="));
    else continue;
    try {
      return findTechnique(name);
    } catch (const InputError&) {
      return fallback;  // the run itself reports the unknown name
    }
  }
  return fallback;
}

void SettingsOptions::add(CLI::App& command, const Technique& help) {
  std::vector<std::string> names;
  for (const auto* t : userTechniques()) names.push_back(t->name);
  techniqueOption =
      command.add_option("--technique", technique,
                         fmt::format("{} (aoreplay techniques lists them), or a user technique's technique.json "
                                     "(a value with '/' or ending in .json; user_techniques/FORMAT.md)",
                                     fmt::join(names, ", ")))
          ->capture_default_str();
  command.add_option("--settings", settingsFile,
                     "settings file (format aoreplay-settings, as `aoreplay tune` writes): technique, preset, keys and "
                     "radius scale; --preset and --set apply on top");
  command.add_option("--preset", preset, fmt::format("presets of {}: {}", help.name, presetTable(help)));
  command.add_option("--set", assignments,
                     fmt::format("KEY=VALUE, repeatable: a key of {} (listed below; --technique NAME --help for "
                                 "another technique's)",
                                 help.name));
  command.add_option("--frames", frames, "half-open frame range A:B (default: all)");
  std::vector<std::string> views;
  for (const auto& v : help.debugViews) views.push_back(v.name);
  command.add_option("--debug", debugViews,
                     fmt::format("read back a debug view of the technique, repeatable: debug/VIEW/NNNN.exr and .png "
                                 "({}: {})", help.name, views.empty() ? "none" : fmt::format("{}", fmt::join(views, ", "))));
  command.footer(fmt::format("Keys of technique {} (--set KEY=VALUE):\n{}", help.name, keyTable(help)));
}

SettingsRecipe SettingsOptions::recipe() const {
  if (settingsFile.empty()) return SettingsRecipe{technique, preset, assignments, 1.0};
  SettingsRecipe recipe = readSettingsFile(settingsFile);
  if (techniqueOption && techniqueOption->count() && technique != recipe.technique)
    throw InputError(settingsFile, std::nullopt, "technique",
                     fmt::format("the file is for technique {}, --technique asks for {}", recipe.technique, technique));
  if (!preset.empty()) recipe.preset = preset;
  recipe.assignments.insert(recipe.assignments.end(), assignments.begin(), assignments.end());
  return recipe;
}

Settings SettingsOptions::resolve(const Capture& capture) const { return recipe().resolve(capture); }

std::pair<int, int> SettingsOptions::frameRange(const Capture& capture) const { return aor::frameRange(capture, frames); }

}  // namespace aor::cli
