// libFuzzer target for settings files (`--settings FILE`, as `aoreplay tune` writes them): the
// input is the file, read with aor::readSettingsFile and, when valid, written back with
// aor::settingsFileJson, which must read back to the same recipe. Bad input must end in
// aor::InputError; a crash, any other exception, a sanitizer report, a disagreement of the bounded
// parser's two paths or a recipe that does not survive its own round trip is a finding.
//
// In the fuzz build (AOR_FUZZ_OWN_REGISTRY) the file names "fuzzed", a technique declared here
// with a key of every type and two presets, because the built-in techniques bring the Vulkan side
// with them; the regression build replays the same inputs against the real registry as well.
#include <cstddef>
#include <cstdint>
#include <fstream>

#include "json_fuzz_support.h"
#include "techniques/registry.h"
#include "techniques/settings_file.h"

namespace {

const aor::Technique& fuzzedTechnique() {
  static const aor::Technique t = [] {
    aor::Technique t;
    t.name = "fuzzed";
    t.parameters = {aor::radiusParameter(1.0), aor::floatParameter("power", 1.0, 0.5, 4.0, "exponent", true),
                    aor::intParameter("slices", 3, 1, 16, "directions", true), aor::boolParameter("bent", true, "bent normals"),
                    aor::enumParameter("mode", {"fast", "fine", "best"}, 0, "a choice")};
    t.presets = {{"low", {{"slices", 1}}}, {"high", {{"slices", 9}, {"mode", 2}}}};
    t.defaultPreset = "high";
    return t;
  }();
  return t;
}

}  // namespace

#ifdef AOR_FUZZ_OWN_REGISTRY
namespace aor {
const Technique& findTechnique(std::string_view name) {
  if (name == fuzzedTechnique().name) return fuzzedTechnique();
  throw InputError("", std::nullopt, "--technique", "unknown technique (the fuzz build knows 'fuzzed')");
}
}  // namespace aor
#else
namespace {
[[maybe_unused]] const bool registered = (aor::registerTechnique(&fuzzedTechnique()), true);
}
#endif

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  aor::fuzz::checkBothParsersAgree(data, size, aor::JsonLimits{std::uint64_t(1) << 20, 10'000, 16});
  const auto file = aor::fuzz::inputFile("settings.json", data, size);
  try {
    const aor::SettingsRecipe recipe = aor::readSettingsFile(file);
    const std::string written = aor::settingsFileJson(recipe).dump(2);
    const auto again = aor::fuzz::inputFile("settings-again.json", reinterpret_cast<const uint8_t*>(written.data()), written.size());
    const aor::SettingsRecipe back = aor::readSettingsFile(again);
    if (back.technique != recipe.technique || back.preset != recipe.preset || back.radiusScale != recipe.radiusScale) __builtin_trap();
  } catch (const aor::InputError&) {
    // The expected outcome for malformed input.
  }
  return 0;
}
