#include "vk/device_selection.h"

#include <algorithm>
#include <cctype>

#include <fmt/format.h>

#include "vk/vk_check.h"

namespace aor {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

bool contains(const std::string& text, const std::string& lowerPiece) { return lower(text).find(lowerPiece) != std::string::npos; }

const DeviceInfo* firstWhere(const std::vector<DeviceInfo>& devices, auto predicate) {
  auto it = std::find_if(devices.begin(), devices.end(), predicate);
  return it == devices.end() ? nullptr : &*it;
}

}  // namespace

std::string deviceListing(const std::vector<DeviceInfo>& devices) {
  std::string names;
  for (const auto& d : devices) names += fmt::format("\n  {}: {} ({})", d.index, d.name, d.driver);
  return names;
}

uint32_t selectDevice(const std::vector<DeviceInfo>& devices, const std::string& selector) {
  if (devices.empty()) throw NoDeviceError("no Vulkan device found (install mesa-vulkan-drivers for lavapipe)");
  if (selector.empty()) {
    const DeviceInfo* lavapipe = firstWhere(devices, [](const auto& d) { return d.isLavapipe; });
    return lavapipe ? lavapipe->index : devices.front().index;
  }
  if (std::all_of(selector.begin(), selector.end(), [](unsigned char c) { return std::isdigit(c); })) {
    if (selector.size() > 9 || std::stoul(selector) >= devices.size())
      throw NoDeviceError(fmt::format("--device {}: no device with that index; devices:{}", selector, deviceListing(devices)));
    return uint32_t(std::stoul(selector));
  }
  const std::string wanted = lower(selector);
  const DeviceInfo* found = nullptr;
  if (wanted == "lavapipe") found = firstWhere(devices, [](const auto& d) { return d.isLavapipe; });
  else if (wanted == "cpu") found = firstWhere(devices, [](const auto& d) { return d.isCpu; });
  if (!found)
    found = firstWhere(devices, [&](const auto& d) { return contains(d.name, wanted) || contains(d.driver, wanted); });
  if (!found)
    throw NoDeviceError(fmt::format("--device {}: no device's name or driver name contains it (aliases: lavapipe, cpu); devices:{}",
                                    selector, deviceListing(devices)));
  return found->index;
}

}  // namespace aor
