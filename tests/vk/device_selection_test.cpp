// --device SEL: index, the aliases lavapipe and cpu, or a piece of the device's or driver's name.
// Fake device lists: no Vulkan needed.
#include <gtest/gtest.h>

#include "vk/device_selection.h"
#include "vk/vk_check.h"

namespace aor {
namespace {

std::vector<DeviceInfo> machine() {
  DeviceInfo gpu{0, "NVIDIA GeForce RTX 4090", "NVIDIA", "", "1.3.277"};
  DeviceInfo swiftshader{1, "SwiftShader Device (Subzero)", "SwiftShader driver", "", "1.3.0"};
  swiftshader.isCpu = true;
  DeviceInfo lavapipe{2, "llvmpipe (LLVM 15.0.6, 256 bits)", "llvmpipe", "Mesa 22.3.6 (LLVM 15.0.6)", "1.3.230"};
  lavapipe.isCpu = lavapipe.isLavapipe = true;
  return {gpu, swiftshader, lavapipe};
}

TEST(DeviceSelection, DefaultIsLavapipeElseTheFirstDevice) {
  EXPECT_EQ(selectDevice(machine(), ""), 2u);
  auto noLavapipe = machine();
  noLavapipe.pop_back();
  EXPECT_EQ(selectDevice(noLavapipe, ""), 0u);
}

TEST(DeviceSelection, AliasesNameTheDriverTheReadmeNames) {
  EXPECT_EQ(selectDevice(machine(), "lavapipe"), 2u);  // it calls itself llvmpipe
  EXPECT_EQ(selectDevice(machine(), "LavaPipe"), 2u);
  EXPECT_EQ(selectDevice(machine(), "cpu"), 1u);  // the first CPU implementation
}

TEST(DeviceSelection, MatchesDeviceNameOrDriverNameCaseInsensitively) {
  EXPECT_EQ(selectDevice(machine(), "llvmpipe"), 2u);
  EXPECT_EQ(selectDevice(machine(), "rtx"), 0u);
  EXPECT_EQ(selectDevice(machine(), "swiftshader driver"), 1u);
  EXPECT_EQ(selectDevice(machine(), "1"), 1u);
}

TEST(DeviceSelection, NoMatchListsTheDevices) {
  try {
    selectDevice(machine(), "radeon");
    FAIL() << "no device matches";
  } catch (const NoDeviceError& e) {
    std::string message = e.what();
    EXPECT_NE(message.find("--device radeon"), std::string::npos) << message;
    EXPECT_NE(message.find("2: llvmpipe (LLVM 15.0.6, 256 bits) (llvmpipe)"), std::string::npos) << message;
    EXPECT_NE(message.find("aliases: lavapipe, cpu"), std::string::npos) << message;
  }
  auto gpuOnly = machine();
  gpuOnly.resize(1);
  EXPECT_THROW(selectDevice(gpuOnly, "lavapipe"), NoDeviceError);
  EXPECT_THROW(selectDevice(gpuOnly, "cpu"), NoDeviceError);
  EXPECT_THROW(selectDevice(machine(), "3"), NoDeviceError);
  EXPECT_THROW(selectDevice(machine(), "99999999999999999999"), NoDeviceError);
  EXPECT_THROW(selectDevice({}, ""), NoDeviceError);
}

}  // namespace
}  // namespace aor
