#include "technique_api/parameters.h"

#include "capture/capture.h"  // kMinAoRadius, kMaxAoRadius: the range loadCapture checks scene.ao_radius against

#include <cmath>
#include <utility>

#include <fmt/format.h>

namespace aor {

const char* parameterTypeName(ParameterType type) {
  switch (type) {
    case ParameterType::Float: return "float";
    case ParameterType::Int: return "int";
    case ParameterType::Bool: return "bool";
    case ParameterType::Enum: return "enum";
  }
  return "?";
}

Parameter floatParameter(std::string key, double defaultValue, double min, double max, std::string doc, bool tunable) {
  return {std::move(key), ParameterType::Float, defaultValue, min, max, {}, tunable, std::move(doc)};
}

Parameter intParameter(std::string key, int defaultValue, int min, int max, std::string doc, bool tunable) {
  return {std::move(key), ParameterType::Int, double(defaultValue), double(min), double(max), {}, tunable, std::move(doc)};
}

Parameter boolParameter(std::string key, bool defaultValue, std::string doc) {
  return {std::move(key), ParameterType::Bool, defaultValue ? 1.0 : 0.0, 0, 1, {}, false, std::move(doc)};
}

Parameter enumParameter(std::string key, std::vector<std::string> choices, int defaultIndex, std::string doc) {
  double last = double(choices.size()) - 1;
  return {std::move(key), ParameterType::Enum, double(defaultIndex), 0, last, std::move(choices), false, std::move(doc)};
}

std::string valueText(const Parameter& p, double value) {
  switch (p.type) {
    case ParameterType::Float: return fmt::format("{}", float(value));  // the float's shortest form: 0.615, not 0.6150000095
    case ParameterType::Int:
    case ParameterType::Bool: return fmt::format("{}", int64_t(value));
    case ParameterType::Enum: {
      size_t index = size_t(value);
      return index < p.choices.size() ? p.choices[index] : fmt::format("{}", value);
    }
  }
  return "?";
}

nlohmann::json jsonValue(const Parameter& p, double value) {
  switch (p.type) {
    case ParameterType::Float: return std::stod(valueText(p, value));
    case ParameterType::Int:
    case ParameterType::Bool: return int64_t(value);
    case ParameterType::Enum: return valueText(p, value);
  }
  return nullptr;
}

std::string describeRange(const Parameter& p) {
  if (p.type == ParameterType::Enum)
    return fmt::format("enum: {} (default {})", fmt::join(p.choices, ", "), valueText(p, p.defaultValue));
  if (p.type == ParameterType::Bool) return fmt::format("bool 0/1, default {}", valueText(p, p.defaultValue));
  return fmt::format("{}, default {}, range [{}, {}]", parameterTypeName(p.type), valueText(p, p.defaultValue),
                     valueText(p, p.min), valueText(p, p.max));
}

Parameter radiusParameter(double fallback) {
  Parameter p = floatParameter(kRadiusKey, fallback, kMinAoRadius, kMaxAoRadius,
                               fmt::format("AO radius in world units; default the capture's scene.ao_radius, else {}", float(fallback)),
                               true);
  p.shared = true;
  return p;
}

}  // namespace aor
