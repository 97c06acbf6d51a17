#pragma once
// `aoreplay --version`: what a bug report needs to reproduce a number.
#include <string>

namespace aor::cli {

// "aoreplay 0.1 (git 6f9ce9a...)", the Vulkan loader's version, then one line per device with its
// driver's name and version text; "no Vulkan driver: ..." in place of the devices when none loads.
std::string versionText();

}  // namespace aor::cli
