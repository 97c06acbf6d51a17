#pragma once
// Which Vulkan device `--device SEL` means. SEL is an index, an alias, or a piece of a device's
// name or driver name (case-insensitive):
//   lavapipe  Mesa's CPU driver (it reports itself as "llvmpipe", driver name "llvmpipe");
//   cpu       the first CPU implementation (lavapipe, SwiftShader, ...).
// Empty: lavapipe if present, else the first device.
#include <cstdint>
#include <string>
#include <vector>

#include "vk/context.h"

namespace aor {

// Index of the chosen device. Throws NoDeviceError listing the devices when none matches.
uint32_t selectDevice(const std::vector<DeviceInfo>& devices, const std::string& selector);

// "  0: llvmpipe (LLVM 15.0.6, 256 bits) (llvmpipe)" per device, for messages and `devices`.
std::string deviceListing(const std::vector<DeviceInfo>& devices);

}  // namespace aor
