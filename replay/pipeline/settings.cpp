#include "pipeline/settings.h"

#include <charconv>
#include <cmath>
#include <functional>

#include <fmt/format.h>

#include "capture/input_error.h"

namespace aor {
namespace {

struct Preset {
  const char* name;
  int slices, steps;
};
constexpr Preset kPresets[] = {{"low", 1, 2}, {"medium", 2, 2}, {"high", 3, 3}, {"ultra", 9, 3}};

struct Key {
  const char* name;
  double min, max;
  bool integer;
  std::function<void(AoSettings&, double)> set;
  const char* help;
};

const std::vector<Key>& keys() {
  static const std::vector<Key> k = {
      {"radius", 1e-6, 1e7, false, [](AoSettings& s, double v) { s.radius = float(v); }, "AO radius in world units"},
      {"slices", 1, 32, true, [](AoSettings& s, double v) { s.slices = int(v); }, "directions per pixel"},
      {"steps", 1, 64, true, [](AoSettings& s, double v) { s.steps = int(v); }, "samples per side of a direction"},
      {"falloff", 0, 1, false, [](AoSettings& s, double v) { s.falloff = float(v); }, "fraction of the radius that fades; 0 = hard cut-off"},
      {"power", 0.05, 16, false, [](AoSettings& s, double v) { s.power = float(v); }, "final exponent, 1 = none"},
      {"thin", 0, 8, false, [](AoSettings& s, double v) { s.thin = float(v); }, "thin-occluder compensation, 0 = off"},
      {"spatial", 0, 1, true, [](AoSettings& s, double v) { s.spatial = int(v); }, "spatial denoise pass 0/1"},
      {"temporal", 0, 0.98, false, [](AoSettings& s, double v) { s.temporal = float(v); }, "history weight, 0 = no temporal pass"},
      {"bent", 0, 1, true, [](AoSettings& s, double v) { s.bent = int(v); }, "bent normals 0/1"},
      {"half_res", 0, 1, true, [](AoSettings& s, double v) { s.halfRes = int(v); },
       "GTAO and spatial blur at half resolution, upsampled by the last pass 0/1"},
  };
  return k;
}

}  // namespace

void applyPreset(AoSettings& settings, std::string_view preset) {
  for (const auto& p : kPresets)
    if (preset == p.name) {
      settings.slices = p.slices;
      settings.steps = p.steps;
      return;
    }
  std::vector<std::string> names;
  for (const auto& p : kPresets) names.push_back(p.name);
  throw InputError("", std::nullopt, "--preset", fmt::format("unknown preset '{}' ({})", preset, fmt::join(names, ", ")));
}

void applySetting(AoSettings& settings, std::string_view assignment) {
  auto eq = assignment.find('=');
  if (eq == std::string_view::npos)
    throw InputError("", std::nullopt, "--set", fmt::format("'{}' is not KEY=VALUE", assignment));
  std::string_view name = assignment.substr(0, eq), text = assignment.substr(eq + 1);
  auto key = std::find_if(keys().begin(), keys().end(), [&](const Key& k) { return name == k.name; });
  if (key == keys().end())
    throw InputError("", std::nullopt, std::string(name), fmt::format("unknown setting '{}'; keys: {}", name, describeSettingKeys()));
  double value = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
    throw InputError("", std::nullopt, std::string(name), fmt::format("'{}' is not a number", text));
  if (key->integer && value != std::floor(value))
    throw InputError("", std::nullopt, std::string(name), fmt::format("{} must be a whole number, got {}", name, text));
  if (value < key->min || value > key->max)
    throw InputError("", std::nullopt, std::string(name), fmt::format("{}={} is out of range [{}, {}]", name, text, key->min, key->max));
  key->set(settings, value);
}

std::string describeSettingKeys() {
  std::string s;
  for (const auto& k : keys()) s += fmt::format("{}{}", s.empty() ? "" : ", ", k.name);
  return s;
}

const char* techniqueName(AoTechnique technique) { return technique == AoTechnique::Reference ? "reference" : "gtao"; }

AoTechnique parseTechnique(std::string_view name) {
  if (name == "gtao") return AoTechnique::Gtao;
  if (name == "reference") return AoTechnique::Reference;
  throw InputError("", std::nullopt, "--technique", fmt::format("unknown technique '{}' (gtao, reference)", name));
}

void applyTechnique(AoSettings& settings, AoTechnique technique) {
  settings.technique = technique;
  if (technique == AoTechnique::Reference) {
    settings.spatial = 0;
    settings.temporal = 0.0f;
    settings.halfRes = 0;
  }
}

// The float's shortest decimal form: 0.615f is reported as 0.615, not 0.6150000095367432.
static double asWritten(float value) { return std::stod(fmt::format("{}", value)); }

nlohmann::json toJson(const AoSettings& s) {
  return {{"technique", techniqueName(s.technique)}, {"radius", asWritten(s.radius)}, {"slices", s.slices},
          {"steps", s.steps}, {"falloff", asWritten(s.falloff)}, {"power", asWritten(s.power)},
          {"thin", asWritten(s.thin)}, {"spatial", s.spatial}, {"temporal", asWritten(s.temporal)}, {"bent", s.bent},
          {"half_res", s.halfRes}};
}

}  // namespace aor
