#include "cli/settings_options.h"

#include <charconv>

#include <fmt/format.h>

#include "pipeline/replayer.h"

namespace aor::cli {

void SettingsOptions::add(CLI::App& command) {
  command.add_option("--preset", preset, "low (1x2), medium (2x2), high (3x3), ultra (9x3) slices x steps")
      ->capture_default_str();
  command.add_option("--set", assignments,
                     "KEY=VALUE, repeatable; keys: radius slices steps falloff power thin spatial temporal bent");
  command.add_option("--frames", frames, "half-open frame range A:B (default: all)");
  command.add_option("--technique", technique,
                     "gtao (default), or reference: the GTAO integral evaluated exhaustively, no noise, no denoise");
}

AoSettings SettingsOptions::resolve(const Capture& capture) const {
  AoSettings base;
  applyPreset(base, preset);
  bool radiusGiven = false;
  for (const auto& a : assignments) radiusGiven |= a.rfind("radius=", 0) == 0;
  AoSettings s = settingsForCapture(capture, base, radiusGiven);
  for (const auto& a : assignments) applySetting(s, a);
  applyTechnique(s, parseTechnique(technique));
  return s;
}

std::pair<int, int> SettingsOptions::frameRange(const Capture& capture) const {
  int total = int(capture.frames.size());
  if (frames.empty()) return {0, total};
  auto colon = frames.find(':');
  auto parse = [&](std::string_view text, int fallback) {
    if (text.empty()) return fallback;
    int value = 0;
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size())
      throw InputError("", std::nullopt, "--frames", fmt::format("'{}' is not A:B with whole numbers", frames));
    return value;
  };
  if (colon == std::string::npos)
    throw InputError("", std::nullopt, "--frames", fmt::format("'{}' is not A:B (half-open, e.g. 3:4)", frames));
  std::string_view text(frames);
  int a = parse(text.substr(0, colon), 0), b = parse(text.substr(colon + 1), total);
  if (a < 0 || a >= b || b > total)
    throw InputError((capture.folder / "capture.json").string(), std::nullopt, "--frames",
                     fmt::format("{} is outside the capture's {} frames (need 0 <= A < B <= {})", frames, total, total));
  return {a, b};
}

}  // namespace aor::cli
