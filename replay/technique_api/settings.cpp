#include "technique_api/settings.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "capture/capture.h"
#include "core/input_error.h"

namespace aor {
namespace {

// Float keys hold what the shaders receive, so equal settings compare equal and print as written.
double stored(const Parameter& p, double value) { return p.type == ParameterType::Float ? double(float(value)) : value; }

double parseValue(const Parameter& p, std::string_view text) {
  std::string_view key = p.key;
  if (p.type == ParameterType::Enum) {
    auto it = std::find(p.choices.begin(), p.choices.end(), text);
    if (it == p.choices.end())
      throw InputError("", std::nullopt, std::string(key),
                       fmt::format("'{}' is not one of {} ({})", text, key, fmt::join(p.choices, ", ")));
    return double(it - p.choices.begin());
  }
  double value = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
    throw InputError("", std::nullopt, std::string(key), fmt::format("'{}' is not a number", text));
  if (p.type != ParameterType::Float && value != std::floor(value))
    throw InputError("", std::nullopt, std::string(key), fmt::format("{} must be a whole number, got {}", key, text));
  if (value < p.min || value > p.max)
    throw InputError("", std::nullopt, std::string(key),
                     fmt::format("{}={} is out of range [{}, {}]", key, text, valueText(p, p.min), valueText(p, p.max)));
  return value;
}

}  // namespace

Settings::Settings(const Technique& technique) : technique_(&technique) {
  for (const auto& p : technique.parameters) values_.push_back(stored(p, p.defaultValue));
  if (!technique.defaultPreset.empty()) applyPreset(technique.defaultPreset);
}

const Technique& Settings::technique() const {
  if (!technique_) throw std::logic_error("settings without a technique");
  return *technique_;
}

size_t Settings::indexOf(std::string_view key) const {
  const auto& params = technique().parameters;
  for (size_t i = 0; i < params.size(); ++i)
    if (params[i].key == key) return i;
  throw std::logic_error(fmt::format("technique {} has no key '{}'", technique_->name, key));
}

double Settings::value(std::string_view key) const { return values_[indexOf(key)]; }

void Settings::set(std::string_view key, double value) {
  size_t i = indexOf(key);
  values_[i] = stored(technique_->parameters[i], value);
}

void Settings::assign(std::string_view key, std::string_view text) {
  const Parameter* p = technique_->parameter(key);
  if (!p)
    throw InputError("", std::nullopt, std::string(key),
                     fmt::format("technique {} has no setting '{}'; its keys: {}", technique_->name, key, technique_->keyList()));
  set(key, parseValue(*p, text));
}

void Settings::assign(std::string_view assignment) {
  auto eq = assignment.find('=');
  if (eq == std::string_view::npos)
    throw InputError("", std::nullopt, "--set", fmt::format("'{}' is not KEY=VALUE", assignment));
  assign(assignment.substr(0, eq), assignment.substr(eq + 1));
}

void Settings::applyPreset(std::string_view name) {
  const Preset* preset = technique_->preset(name);
  if (!preset)
    throw InputError("", std::nullopt, "--preset",
                     fmt::format("technique {} has no preset '{}' (presets: {})", technique_->name, name, technique_->presetList()));
  for (const auto& [key, value] : preset->values) set(key, value);
}

std::string Settings::text(std::string_view key) const {
  size_t i = indexOf(key);
  return valueText(technique_->parameters[i], values_[i]);
}

nlohmann::json Settings::toJson() const {
  nlohmann::json out{{"technique", technique().name}};
  const auto& params = technique().parameters;
  for (size_t i = 0; i < params.size(); ++i) out[params[i].key] = jsonValue(params[i], values_[i]);
  return out;
}

std::optional<double> captureRadius(const Capture& capture) {
  if (!capture.scene.contains("ao_radius")) return std::nullopt;
  const auto& value = capture.scene["ao_radius"];
  std::string file = (capture.folder / "capture.json").string();
  if (!value.is_number()) throw InputError(file, std::nullopt, "scene.ao_radius", "must be a number");
  double r = value.get<double>();
  Parameter range = radiusParameter(1.0);
  if (!(r >= range.min && r <= range.max))
    throw InputError(file, std::nullopt, "scene.ao_radius",
                     fmt::format("must be a positive number in [{}, {}] world units, got {}", range.min, range.max, r));
  return r;
}

bool assignsRadius(const std::vector<std::string>& assignments) {
  return std::any_of(assignments.begin(), assignments.end(),
                     [](const std::string& a) { return a.rfind(std::string(kRadiusKey) + "=", 0) == 0; });
}

Settings resolveSettings(const Technique& technique, const Capture& capture, std::string_view preset,
                         const std::vector<std::string>& assignments) {
  Settings s(technique);
  if (!preset.empty()) s.applyPreset(preset);
  if (auto r = captureRadius(capture); r && !assignsRadius(assignments) && s.has(kRadiusKey)) s.set(kRadiusKey, *r);
  for (const auto& a : assignments) s.assign(a);
  return s;
}

}  // namespace aor
