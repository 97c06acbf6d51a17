#pragma once
// Texels read back from the GPU turned into floats: the frame's output (visibility, bent normals)
// and debug views, whatever format a technique wrote them in.
#include <cstdint>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "technique_api/frame_builder.h"

namespace aor {

// Channels of a format the read-back can decode (0 for one it cannot).
uint32_t decodableChannels(VkFormat format);
// Every texel of a tightly packed width x height image in `format` as `channels` floats
// (decodableChannels) per texel; integer formats as their values.
std::vector<float> decodeTexels(const void* data, VkFormat format, size_t texels);

struct DecodedOutput {
  std::vector<float> visibility;  // width*height
  std::vector<float> bent;        // width*height*3, empty without bent normals
};
DecodedOutput decodeOutput(const void* data, VkFormat format, const OutputLayout& layout, size_t pixels);

// A debug view read back: channels floats per texel.
struct DebugImage {
  std::string name;
  int width = 0, height = 0;
  uint32_t channels = 0;
  std::vector<float> values;
};
// A debug buffer read back as 32-bit unsigned counters.
struct DebugCounters {
  std::string name;
  std::vector<uint32_t> values;
};

}  // namespace aor
