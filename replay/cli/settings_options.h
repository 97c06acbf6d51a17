#pragma once
// Options shared by commands that take a capture and a technique's settings (run, graph), and the
// help text of a technique's keys: both read the technique's declarations (technique_api/technique.h).
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "capture/capture.h"
#include "technique_api/settings.h"
#include "techniques/registry.h"
#include "techniques/settings_file.h"

namespace aor::cli {

struct SettingsOptions {
  std::string technique = defaultTechnique().name;  // --technique NAME
  std::string preset;                    // --preset (empty: the technique's default)
  std::vector<std::string> assignments;  // --set KEY=VALUE
  std::string settingsFile;              // --settings FILE (techniques/settings_file.h)
  std::string frames;                    // --frames A:B (half-open)
  std::vector<std::string> debugViews;   // --debug VIEW
  const CLI::Option* techniqueOption = nullptr;  // set by add(): whether --technique was given
  // Adds the options; the help lists `helpTechnique`'s presets and keys (the one named by
  // --technique on the command line, else the default).
  void add(CLI::App& command, const Technique& helpTechnique);
  // The technique, its preset, the capture's scene.ao_radius, then --set in order. Throws InputError.
  Settings resolve(const Capture& capture) const;
  // What the options ask for before a capture is known: --settings FILE's recipe (its technique,
  // preset and keys; --preset and --set given too go on top, a different --technique is refused),
  // else --technique, --preset and --set. Throws InputError.
  SettingsRecipe recipe() const;
  // Parses --frames against the capture; {0, frames} when not given.
  std::pair<int, int> frameRange(const Capture& capture) const;
};

// The technique the command line names with --technique (for help text), else `fallback`.
const Technique& techniqueForHelp(int argc, const char* const* argv, const Technique& fallback);
// One line per key: "  radius    float, default 1, range [1e-06, 1e+07]: AO radius ...".
std::string keyTable(const Technique& technique);
// "low (slices=1 steps=2), medium (...), high (default)".
std::string presetTable(const Technique& technique);

}  // namespace aor::cli
