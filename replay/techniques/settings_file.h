#pragma once
// A settings file (format "aoreplay-settings", version 1; docs/tuning.md): a technique, a preset,
// key values and a radius scale, applied to any capture. `aoreplay tune` writes one; `run`, `graph`
// and `sweep` read it with --settings FILE (and `ab` through its sides' run arguments).
//   { "format": "aoreplay-settings", "version": 1, "technique": "gtao", "preset": "high",
//     "set": {"power": 2.2, "falloff": 0.6}, "radius_scale": 1.457 }
// "preset", "set" and "radius_scale" are optional. The radius is a scale of each capture's own
// scene.ao_radius, because captures differ in scale (world units): a radius tuned on one capture
// means nothing on another, a ratio to the scene's AO radius does. "set" may not hold "radius".
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "capture/capture.h"
#include "technique_api/settings.h"

namespace aor {

inline constexpr const char* kSettingsFormat = "aoreplay-settings";
inline constexpr int kSettingsVersion = 1;

// What a settings file or a command line asks for, before a capture is known.
struct SettingsRecipe {
  std::string technique;
  std::string preset;                    // empty: the technique's default
  std::vector<std::string> assignments;  // KEY=VALUE in order
  double radiusScale = 1.0;              // times the capture's scene.ao_radius (or the default)
  // The settings for one capture: resolveSettings(), then the radius scaled unless an assignment
  // names the radius. Throws InputError.
  Settings resolve(const Capture& capture) const;
};

// Reads and checks a settings file: format, version, unknown fields, the technique, its preset,
// every key and value (range-checked against the technique's declarations). Throws InputError
// naming the file and the field.
SettingsRecipe readSettingsFile(const std::filesystem::path& path);
// The file's JSON for `recipe` (keys in the technique's declaration order).
nlohmann::json settingsFileJson(const SettingsRecipe& recipe);

}  // namespace aor
