#include "techniques/settings_file.h"

#include <cmath>
#include <set>

#include <fmt/format.h>

#include "core/input_error.h"
#include "core/json_input.h"
#include "core/plain_text.h"
#include "techniques/registry.h"

namespace aor {
namespace {

using nlohmann::json;

// A "set" value as the text `--set KEY=VALUE` takes, so both paths share one parser and its checks.
std::string assignmentText(const std::string& file, const std::string& key, const json& value) {
  if (value.is_boolean()) return value.get<bool>() ? "1" : "0";
  if (value.is_number_integer()) return fmt::format("{}", value.get<int64_t>());
  if (value.is_number()) return fmt::format("{}", value.get<double>());
  if (value.is_string()) return withoutControlCharacters(value.get<std::string>(), file, "set." + key);
  throw InputError(file, std::nullopt, "set." + key, "must be a number, a boolean or an enum choice's name");
}

std::string stringField(const std::string& file, const json& j, const char* key) {
  if (!j.at(key).is_string()) throw InputError(file, std::nullopt, key, "must be a string");
  return withoutControlCharacters(j.at(key).get<std::string>(), file, key);
}

void checkHeader(const std::string& file, const json& j) {
  if (!j.is_object()) throw InputError(file, std::nullopt, "", "must be a JSON object");
  static const std::set<std::string> known{"format", "version", "technique", "preset", "set", "radius_scale"};
  for (const auto& [key, value] : j.items())
    if (!known.count(key))
      throw InputError(file, std::nullopt, key, "unknown field (known: format, version, technique, preset, set, radius_scale)");
  if (!j.contains("format") || j["format"] != kSettingsFormat)
    throw InputError(file, std::nullopt, "format", fmt::format("must be \"{}\"", kSettingsFormat));
  if (!j.contains("version") || !j["version"].is_number_integer() || j["version"].get<int64_t>() != kSettingsVersion)
    throw InputError(file, std::nullopt, "version", fmt::format("must be {} (this build reads version {})", kSettingsVersion, kSettingsVersion));
  if (!j.contains("technique")) throw InputError(file, std::nullopt, "technique", "missing");
}

double radiusScaleField(const std::string& file, const json& j) {
  if (!j.contains("radius_scale")) return 1.0;
  const json& v = j["radius_scale"];
  double scale = v.is_number() ? v.get<double>() : NAN;
  if (!(scale >= 1e-3 && scale <= 1e3))
    throw InputError(file, std::nullopt, "radius_scale", "must be a number in [0.001, 1000] (a factor on the capture's scene.ao_radius)");
  return scale;
}

// Resolving against a throw-away capture checks every key, value and the preset now, so a bad
// file fails when it is read rather than at the first capture.
void checkAgainstTechnique(const std::string& file, const SettingsRecipe& recipe) {
  const Technique& technique = findTechnique(recipe.technique);
  try {
    Settings s(technique);
    if (!recipe.preset.empty()) s.applyPreset(recipe.preset);
    for (const auto& a : recipe.assignments) s.assign(a);
  } catch (const InputError& e) {
    throw InputError(file, std::nullopt, e.field.empty() ? "set" : "set." + e.field, e.what());
  }
}

}  // namespace

Settings SettingsRecipe::resolve(const Capture& capture) const {
  Settings s = resolveSettings(findTechnique(technique), capture, preset, assignments);
  if (radiusScale != 1.0 && !assignsRadius(assignments) && s.has(kRadiusKey)) {
    const Parameter& range = *s.technique().parameter(kRadiusKey);
    s.set(kRadiusKey, std::clamp(s.value(kRadiusKey) * radiusScale, range.min, range.max));
  }
  return s;
}

SettingsRecipe readSettingsFile(const std::filesystem::path& path) {
  const std::string file = path.string();
  const json j = readBoundedJson(path, JsonLimits{std::uint64_t(1) << 20, 10'000, 16});
  checkHeader(file, j);
  SettingsRecipe recipe;
  recipe.technique = stringField(file, j, "technique");
  if (j.contains("preset")) recipe.preset = stringField(file, j, "preset");
  if (j.contains("set")) {
    if (!j["set"].is_object()) throw InputError(file, std::nullopt, "set", "must be an object of KEY: VALUE");
    for (const auto& [key, value] : j["set"].items()) {
      if (key == kRadiusKey)
        throw InputError(file, std::nullopt, "set.radius", "a settings file scales each capture's radius: use radius_scale");
      recipe.assignments.push_back(key + "=" + assignmentText(file, key, value));
    }
  }
  recipe.radiusScale = radiusScaleField(file, j);
  try {
    checkAgainstTechnique(file, recipe);
  } catch (const InputError& e) {
    if (e.file == file) throw;
    throw InputError(file, std::nullopt, "technique", e.what());  // an unknown technique
  }
  return recipe;
}

json settingsFileJson(const SettingsRecipe& recipe) {
  const Technique& technique = findTechnique(recipe.technique);
  Settings s(technique);
  if (!recipe.preset.empty()) s.applyPreset(recipe.preset);
  for (const auto& a : recipe.assignments) s.assign(a);
  json set = json::object();
  for (const auto& a : recipe.assignments) {
    std::string key = a.substr(0, a.find('='));
    set[key] = jsonValue(*technique.parameter(key), s.value(key));
  }
  json j{{"format", kSettingsFormat}, {"version", kSettingsVersion}, {"technique", recipe.technique}};
  if (!recipe.preset.empty()) j["preset"] = recipe.preset;
  j["set"] = set;
  j["radius_scale"] = recipe.radiusScale;
  return j;
}

}  // namespace aor
