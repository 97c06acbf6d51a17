// libFuzzer target for a user technique's technique.json (`--technique PATH`): the input is the
// file, read with aor::loadUserTechniqueSpec in a folder that holds the shaders the seeds name, and
// when valid each pass's generated aoreplay.glsl is written (aor::userPassHeader), as a run and
// `aoreplay technique-header` do. Bad input must end in aor::InputError; a crash, any other
// exception, a sanitizer report or a disagreement of the bounded parser's two paths is a finding.
// No shader is compiled: libshaderc is not part of the fuzz build.
#include <cstddef>
#include <cstdint>
#include <fstream>

#include "json_fuzz_support.h"
#include "techniques/user/user_header.h"
#include "techniques/user/user_technique_spec.h"

namespace {

// The files the seeds' passes and includes name, beside the input.
void writeShaders(const std::filesystem::path& folder) {
  static bool written = false;
  if (written) return;
  for (const char* name : {"shade.comp", "blur.comp", "ssao.comp"})
    std::ofstream(folder / name) << "#version 450\n#include \"aoreplay.glsl\"\nvoid main() {}\n";
  std::filesystem::create_directories(folder / "lib");
  std::ofstream(folder / "lib" / "common.glsl") << "const float kPi = 3.14159265;\n";
  written = true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  aor::fuzz::checkBothParsersAgree(data, size, aor::JsonLimits{std::uint64_t(1) << 20, 1'000'000, 128});
  const auto file = aor::fuzz::inputFile("technique.json", data, size);
  writeShaders(file.parent_path());
  try {
    const auto spec = aor::loadUserTechniqueSpec(file, "technique.json");
    for (const auto& pass : spec.passes) (void)aor::userPassHeader(spec, pass);
  } catch (const aor::InputError&) {
    // The expected outcome for malformed input.
  }
  return 0;
}
