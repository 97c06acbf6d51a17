#include "cli/version.h"

#include <fmt/format.h>

#include "vk/context.h"
#include "vk/vk_check.h"

namespace aor::cli {

extern const char* const kGitCommit;  // build/replay/git_commit.cpp, written by cli/git_commit.cmake

std::string versionText() {
  std::string text = fmt::format("aoreplay {} (git {})\nVulkan loader: {}\n", AOREPLAY_VERSION, kGitCommit, loaderVersion());
  try {
    for (const auto& d : listDevices())
      text += fmt::format("device {}: {}; driver {} {}; Vulkan {}\n", d.index, d.name, d.driver, d.driverInfo, d.apiVersion);
  } catch (const NoDeviceError& e) {
    text += fmt::format("no Vulkan driver: {}\n", e.what());
  } catch (const VulkanError& e) {
    text += fmt::format("no Vulkan driver: {}\n", e.what());
  }
  return text;
}

}  // namespace aor::cli
