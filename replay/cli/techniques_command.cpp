// `aoreplay techniques [--json]`: every technique with its seed, presets, inputs, debug views and
// keys (type, default, range, doc), from the techniques' own declarations.
#include <memory>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/handlers.h"
#include "cli/settings_options.h"
#include "techniques/registry.h"

namespace aor::cli {
namespace {

const char* inputUseName(InputUse use) {
  switch (use) {
    case InputUse::Unused: return "unused";
    case InputUse::Optional: return "optional";
    case InputUse::Required: return "required";
  }
  return "?";
}

nlohmann::json parameterJson(const Parameter& p) {
  nlohmann::json j{{"key", p.key},           {"type", parameterTypeName(p.type)}, {"default", jsonValue(p, p.defaultValue)},
                   {"tunable", p.tunable},   {"shared", p.shared},                {"doc", p.doc}};
  if (p.type == ParameterType::Enum) {
    j["choices"] = p.choices;
  } else {
    j["min"] = jsonValue(p, p.min);
    j["max"] = jsonValue(p, p.max);
  }
  return j;
}

nlohmann::json techniqueJson(const Technique& t) {
  nlohmann::json presets = nlohmann::json::object();
  for (const auto& p : t.presets) {
    nlohmann::json values = nlohmann::json::object();
    for (const auto& [key, value] : p.values) values[key] = jsonValue(*t.parameter(key), value);
    presets[p.name] = values;
  }
  nlohmann::json params = nlohmann::json::array();
  for (const auto& p : t.parameters) params.push_back(parameterJson(p));
  nlohmann::json views = nlohmann::json::array();
  for (const auto& v : t.debugViews) views.push_back({{"name", v.name}, {"doc", v.doc}});
  return {{"name", t.name},
          {"file", t.file},
          {"seed", t.seed},
          {"summary", t.summary},
          {"presets", presets},
          {"default_preset", t.defaultPreset},
          {"inputs", {{"depth", "required"}, {"normals", inputUseName(t.inputs.normals)}, {"depth2", inputUseName(t.inputs.depth2)}}},
          {"debug_views", views},
          {"parameters", params}};
}

std::string techniqueText(const Technique& t) {
  std::string out = fmt::format("{}{}\n  {}\n", t.name, t.seed.empty() ? "" : fmt::format(" (seed {})", t.seed), t.summary);
  out += fmt::format("  presets: {}\n", presetTable(t));
  out += fmt::format("  inputs: depth; normals {} (without: reconstructed from depth); second depth layer {}\n",
                     inputUseName(t.inputs.normals), inputUseName(t.inputs.depth2));
  if (!t.debugViews.empty()) {
    out += "  debug views (--debug):\n";
    for (const auto& v : t.debugViews) out += fmt::format("    {}: {}\n", v.name, v.doc);
  }
  out += "  keys (--set KEY=VALUE):\n";
  std::string keys = keyTable(t);
  for (size_t start = 0; start < keys.size();) {
    size_t nl = keys.find('\n', start);
    out += "  " + keys.substr(start, nl - start + 1);
    start = nl + 1;
  }
  return out;
}

}  // namespace

void registerTechniquesCommand(CLI::App& app) {
  auto json = std::make_shared<bool>(false);
  auto files = std::make_shared<std::vector<std::string>>();
  auto* cmd = app.add_subcommand("techniques", "list every technique: seed, presets, inputs, debug views and keys");
  cmd->add_flag("--json", *json, "as JSON");
  cmd->add_option("--technique", *files, "a user technique's technique.json to list after the built-ins, repeatable");
  handlers()["techniques"] = [json, files] {
    for (const auto& file : *files) findTechnique(file);  // loaded (and checked): listed below
    if (*json) {
      nlohmann::json list = nlohmann::json::array();
      for (const auto* t : userTechniques()) list.push_back(techniqueJson(*t));
      fmt::print("{}\n", nlohmann::json{{"techniques", list}}.dump(2));
      return kExitOk;
    }
    bool first = true;
    for (const auto* t : userTechniques()) {
      fmt::print("{}{}", first ? "" : "\n", techniqueText(*t));
      first = false;
    }
    return kExitOk;
  };
}

}  // namespace aor::cli
