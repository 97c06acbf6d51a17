#pragma once
// A run's settings: the technique and a value for every key it declares. `--set`, presets and the
// capture's default radius are applied through here, with range checks; the same object keys
// history validity (history recorded under other settings is never blended).
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "technique_api/technique.h"

namespace aor {

class Settings {
 public:
  // The technique's defaults, then its default preset.
  explicit Settings(const Technique& technique);
  // No technique yet (a field to be assigned); using it throws std::logic_error.
  Settings() = default;

  const Technique& technique() const;
  bool has(std::string_view key) const { return technique().parameter(key) != nullptr; }
  double value(std::string_view key) const;  // throws std::logic_error for a key the technique lacks
  float f(std::string_view key) const { return float(value(key)); }
  int i(std::string_view key) const { return int(value(key)); }
  bool b(std::string_view key) const { return value(key) != 0.0; }
  // Sets a declared key without checks (techniques and tests; users go through assign()). Float
  // keys hold the float the shaders get.
  void set(std::string_view key, double value);

  // "KEY=VALUE": unknown keys (the message lists the technique's), malformed values, fractions for
  // whole keys, unknown enum choices and values out of range throw InputError naming the key.
  void assign(std::string_view assignment);
  void assign(std::string_view key, std::string_view text);
  // The preset's values; an unknown preset throws InputError listing the technique's presets.
  void applyPreset(std::string_view preset);

  bool operator==(const Settings& other) const { return technique_ == other.technique_ && values_ == other.values_; }
  // {"technique": NAME, KEY: VALUE, ...}: floats in their shortest form, whole keys as integers,
  // enums by name.
  nlohmann::json toJson() const;
  std::string text(std::string_view key) const;  // the value as a user writes it

 private:
  size_t indexOf(std::string_view key) const;
  const Technique* technique_ = nullptr;
  std::vector<double> values_;  // parallel to technique_->parameters
};

// Settings for a capture: the technique's defaults, its preset (the default one when `preset` is
// empty), the capture's scene.ao_radius as the radius unless an assignment sets it, then the
// assignments in order. Throws InputError.
Settings resolveSettings(const Technique& technique, const Capture& capture, std::string_view preset,
                         const std::vector<std::string>& assignments);
// Whether one of the KEY=VALUE assignments sets the radius (it then wins over the capture's).
bool assignsRadius(const std::vector<std::string>& assignments);
// The capture's scene.ao_radius, checked; none when the capture has none.
std::optional<double> captureRadius(const Capture& capture);

}  // namespace aor
