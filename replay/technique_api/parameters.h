#pragma once
// The keys a technique declares (`--set KEY=VALUE`): type, default, range, doc, and whether
// `aoreplay tune` may search it. CLI help, `--set` parsing, sweep columns, report.json settings and
// `aoreplay techniques` all read these declarations; nothing keeps a second list.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace aor {

enum class ParameterType { Float, Int, Bool, Enum };
const char* parameterTypeName(ParameterType type);  // "float", "int", "bool", "enum"

struct Parameter {
  std::string key;
  ParameterType type = ParameterType::Float;
  double defaultValue = 0;
  double min = 0, max = 0;           // inclusive; Bool 0..1, Enum 0..choices-1
  std::vector<std::string> choices;  // Enum: the values' names, in index order
  bool tunable = false;              // a continuous or integer key `aoreplay tune` searches by default
  std::string doc;                   // one line
  // A key of the run or of a shared block (radius, spatial, temporal) rather than the technique's
  // own: every technique that has one means the same by it, and a user technique may not redeclare it.
  bool shared = false;
};

Parameter floatParameter(std::string key, double defaultValue, double min, double max, std::string doc, bool tunable = false);
Parameter intParameter(std::string key, int defaultValue, int min, int max, std::string doc, bool tunable = false);
Parameter boolParameter(std::string key, bool defaultValue, std::string doc);
Parameter enumParameter(std::string key, std::vector<std::string> choices, int defaultIndex, std::string doc);

// A value as text the way a user writes it: "0.615", "3", "1", "compute".
std::string valueText(const Parameter& parameter, double value);
// A value in JSON (report.json, `aoreplay techniques --json`): floats in their shortest form, whole
// keys as integers, enums by name.
nlohmann::json jsonValue(const Parameter& parameter, double value);
// "float, default 0.615, range [0, 1]" (or "choices: a, b (default a)").
std::string describeRange(const Parameter& parameter);

// The run's AO radius in world units, every technique's: the capture's scene.ao_radius replaces
// `fallback` as its default, and `--set radius=` replaces both.
inline constexpr const char* kRadiusKey = "radius";
Parameter radiusParameter(double fallback);

}  // namespace aor
