#pragma once
// Options shared by commands that take a capture and AO settings (run, graph).
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "capture/capture.h"
#include "pipeline/settings.h"

namespace aor::cli {

struct SettingsOptions {
  std::string preset = "high";
  std::string technique = "gtao";        // --technique gtao|reference
  std::vector<std::string> assignments;  // --set KEY=VALUE
  std::string frames;                    // --frames A:B (half-open)
  void add(CLI::App& command);
  // Preset, then the capture's scene.ao_radius, then --set in order. Throws InputError.
  AoSettings resolve(const Capture& capture) const;
  // Parses --frames against the capture; {0, frames} when not given.
  std::pair<int, int> frameRange(const Capture& capture) const;
};

}  // namespace aor::cli
