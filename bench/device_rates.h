#pragma once
// A device's measured rates, the denominators of a pass's floor (bench/floor.h): the bandwidth of
// buffer copies (vkCmdCopyBuffer and a compute shader's copy, bytes read plus bytes written per
// ms) at sizes from 1 MiB up to the largest asked, the rate of texelFetch from an R32F image in
// cache (fetch_rate.comp), and the time one empty dispatch adds to a chain of them; each from the
// median of `reps` timed runs after a warm-up, from timestamp queries.
//
// Why several copy sizes: a floor is the least time the work can take, and a pass's images are
// often still in the last-level cache from the pass that wrote them (an H200's L2 holds 50 MB, a
// 4K R32F image is 33 MB), so DRAM bandwidth alone overstates the floor (measured / floor fell to
// x0.33 on linearize_depth). The floor uses the fastest copy measured; every size's rate is kept.
#include <cstdint>
#include <utility>
#include <vector>

#include "vk/context.h"

namespace aor::bench {

// vkCmdCopyBuffer, or copy_rate.comp's storage-buffer copy: a pass moves its bytes through the
// shader's load/store path, which on a GPU whose copies run on a copy engine is the faster one
// (an H200: 0.85 TB/s by vkCmdCopyBuffer, below what its blur passes were measured to move).
enum class CopyPath { Transfer, Shader };
inline const char* copyPathName(CopyPath p) { return p == CopyPath::Transfer ? "vkCmdCopyBuffer" : "shader"; }

struct CopyRate {
  uint64_t bytes = 0;       // the copied buffer's size
  double bytesPerMs = 0;    // read + written
  CopyPath path = CopyPath::Transfer;
};

// texelFetch of taps scattered out to `spread` pixels along directions that turn per pixel, as a
// horizon search's (fetch_rate.comp): not a floor, an explanation of a pass far above its floor.
struct ScatteredFetchRate {
  int spread = 0;
  double texelFetchesPerMs = 0;
};
inline constexpr int kScatteredFetchSpreads[] = {8, 32, 128};

struct DeviceRates {
  double copyBytesPerMs = 0;     // the fastest of `copies`
  double texelFetchesPerMs = 0;
  double dispatchMs = 0;         // one dispatch of one workgroup in a chain of them, the least any pass can take
  uint64_t copyBytes = 0;        // the size the fastest copy ran at
  CopyPath copyPath = CopyPath::Transfer;  // and its path
  std::vector<CopyRate> copies;  // 1 MiB, 4 MiB, ... up to the largest asked, each by both paths
  std::pair<int, int> fetchSize;  // the fetch kernel's grid
  std::vector<ScatteredFetchRate> scatteredFetches;  // kScatteredFetchSpreads, on the same grid
};

// `copyBytes`: the largest copy.
DeviceRates measureDeviceRates(VulkanContext& vk, uint64_t copyBytes, std::pair<int, int> fetchSize, int reps,
                               double warmupMs);

}  // namespace aor::bench
