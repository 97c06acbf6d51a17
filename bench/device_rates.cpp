#include "device_rates.h"

#include <algorithm>
#include <chrono>
#include <vector>

#include "embedded_shaders.h"
#include "shaders/copy_rate.h"
#include "shaders/fetch_rate.h"
#include "timed_rig.h"
#include "vk/dispatch.h"
#include "vk/resources.h"

namespace aor::spirv {
std::span<const EmbeddedShader> aor_bench_shaders();  // generated index of bench/shaders/ (shaders/CMakeLists.txt)
}  // namespace aor::spirv

namespace aor::bench {
namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Runs `once` until `warmupMs` of wall time have passed (a GPU leaves its idle clocks), then `reps`
// times; the median GPU time.
template <class Once>
double medianMs(Once&& once, int reps, double warmupMs) {
  auto start = std::chrono::steady_clock::now();
  do once();
  while (std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() < warmupMs);
  std::vector<double> ms;
  for (int r = 0; r < reps; ++r) ms.push_back(once());
  return median(ms);
}

double copyMs(Rig& rig, uint64_t bytes, int reps, double warmupMs) {
  VulkanContext& vk = rig.vk;
  GpuBuffer from = createDeviceBuffer(vk, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  GpuBuffer to = createDeviceBuffer(vk, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  rig.timed([&](VkCommandBuffer cmd) { vkCmdFillBuffer(cmd, from.buffer, 0, VK_WHOLE_SIZE, 0x3f800000u); });
  VkBufferCopy region{0, 0, bytes};
  double ms = medianMs([&] { return rig.timed([&](VkCommandBuffer cmd) { vkCmdCopyBuffer(cmd, from.buffer, to.buffer, 1, &region); }); },
                       reps, warmupMs);
  destroyBuffer(vk, to);
  destroyBuffer(vk, from);
  return ms;
}

// The same bytes copied by copy_rate.comp: the load/store path passes use.
double shaderCopyMs(Rig& rig, uint64_t bytes, int reps, double warmupMs) {
  VulkanContext& vk = rig.vk;
  GpuBuffer from = createDeviceBuffer(vk, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  GpuBuffer to = createDeviceBuffer(vk, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  rig.timed([&](VkCommandBuffer cmd) { vkCmdFillBuffer(cmd, from.buffer, 0, VK_WHOLE_SIZE, 0x3f800000u); });
  ComputePipeline pipeline = createComputePipeline(vk, spirv::code("copy_rate", spirv::aor_bench_shaders()), "copy_rate");
  BoundResource bound[2];
  bound[0].buffer = from.buffer;
  bound[1].buffer = to.buffer;
  shader::CopyRateConstants constants{uint32_t(bytes / 16)};
  uint64_t groups = (constants.vec4s + shader::kCopyRateWorkgroupSize - 1) / shader::kCopyRateWorkgroupSize;
  DispatchGroups grid{uint32_t(std::min<uint64_t>(groups, shader::kCopyRateMaxGroups)), 1, 1};
  VkMemoryBarrier2 filled{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  filled.srcStageMask = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
  filled.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
  filled.dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
  filled.dstAccessMask = VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
  double ms = medianMs(
      [&] {
        return rig.timed([&](VkCommandBuffer cmd) {
          VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
          dependency.memoryBarrierCount = 1;
          dependency.pMemoryBarriers = &filled;
          vkCmdPipelineBarrier2(cmd, &dependency);
          recordDispatch(vk, cmd, pipeline, bound, &constants, grid);
        });
      },
      reps, warmupMs);
  destroyPipeline(vk, pipeline);
  destroyBuffer(vk, to);
  destroyBuffer(vk, from);
  return ms;
}

void toGeneral(VkCommandBuffer cmd, VkImage image, VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
  VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  b.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  b.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
  b.dstStageMask = dstStage;
  b.dstAccessMask = dstAccess;
  b.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  b.newLayout = VK_IMAGE_LAYOUT_GENERAL;
  b.image = image;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.imageMemoryBarrierCount = 1;
  dependency.pImageMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &dependency);
}

// The fetch kernel over a width x height grid, its taps `spread` pixels out at most (0: the 8x8
// neighbourhood), `chain` dispatches back to back (a barrier between each two, as a graph puts
// between passes): milliseconds for the chain. On a 1x1 grid (one workgroup, one live invocation)
// it times what dispatches cost before they do any work.
double fetchMs(Rig& rig, std::pair<int, int> size, int reps, double warmupMs, int spread = 0, int chain = 1) {
  VulkanContext& vk = rig.vk;
  auto [width, height] = size;
  GpuImage source = createImage(vk, width + shader::kFetchRatePad, height + shader::kFetchRatePad, VK_FORMAT_R32_SFLOAT,
                                VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
  GpuImage target = createImage(vk, width, height, VK_FORMAT_R32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT);
  SpecializationValue spreadValue{0, uint32_t(spread)};
  ComputePipeline pipeline = createComputePipeline(vk, spirv::code("fetch_rate", spirv::aor_bench_shaders()), "fetch_rate",
                                                   {&spreadValue, 1});
  rig.timed([&](VkCommandBuffer cmd) {
    toGeneral(cmd, source.image, VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    VkClearColorValue half{{0.5f, 0.5f, 0.5f, 0.5f}};
    VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(cmd, source.image, VK_IMAGE_LAYOUT_GENERAL, &half, 1, &all);
    toGeneral(cmd, target.image, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  });
  VkMemoryBarrier2 cleared{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  cleared.srcStageMask = VK_PIPELINE_STAGE_2_CLEAR_BIT;
  cleared.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
  cleared.dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
  cleared.dstAccessMask = VK_ACCESS_2_SHADER_SAMPLED_READ_BIT;
  VkMemoryBarrier2 chained{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  chained.srcStageMask = chained.dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
  chained.srcAccessMask = chained.dstAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
  BoundResource bound[2];
  bound[0].view = source.view;
  bound[1].view = target.view;
  bound[0].layout = bound[1].layout = VK_IMAGE_LAYOUT_GENERAL;
  shader::FetchRateConstants constants{{width, height}};
  auto once = [&] {
    return rig.timed([&](VkCommandBuffer cmd) {
      VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
      dependency.memoryBarrierCount = 1;
      dependency.pMemoryBarriers = &cleared;
      vkCmdPipelineBarrier2(cmd, &dependency);
      for (int k = 0; k < chain; ++k) {
        if (k > 0) {
          dependency.pMemoryBarriers = &chained;
          vkCmdPipelineBarrier2(cmd, &dependency);
        }
        recordDispatch(vk, cmd, pipeline, bound, &constants, groupsFor(pipeline, width, height));
      }
    });
  };
  double ms = medianMs(once, reps, warmupMs);
  destroyPipeline(vk, pipeline);
  destroyImage(vk, target);
  destroyImage(vk, source);
  return ms;
}

}  // namespace

DeviceRates measureDeviceRates(VulkanContext& vk, uint64_t copyBytes, std::pair<int, int> fetchSize, int reps, double warmupMs) {
  Rig rig(vk);
  DeviceRates rates;
  rates.fetchSize = fetchSize;
  for (uint64_t bytes = std::min<uint64_t>(copyBytes, 1u << 20);; bytes = std::min(bytes * 4, copyBytes)) {
    for (CopyPath path : {CopyPath::Transfer, CopyPath::Shader}) {
      double ms = path == CopyPath::Transfer ? copyMs(rig, bytes, reps, warmupMs) : shaderCopyMs(rig, bytes, reps, warmupMs);
      CopyRate copy{bytes, 2.0 * double(bytes) / ms, path};
      rates.copies.push_back(copy);
      if (copy.bytesPerMs > rates.copyBytesPerMs) {
        rates.copyBytesPerMs = copy.bytesPerMs;
        rates.copyBytes = bytes;
        rates.copyPath = path;
      }
    }
    if (bytes == copyBytes) break;
  }
  double fetches = double(fetchSize.first) * fetchSize.second * shader::kFetchRateTaps;
  rates.texelFetchesPerMs = fetches / fetchMs(rig, fetchSize, reps, warmupMs);
  for (int spread : kScatteredFetchSpreads)
    rates.scatteredFetches.push_back({spread, fetches / fetchMs(rig, fetchSize, reps, warmupMs, spread)});
  // A pass inside a frame does not pay a lone dispatch's submission-edge cost: the empty
  // dispatch's floor is the slope of a chain of them (on an H200 a lone one took 0.0057 ms, more
  // than SAO's smallest MIP passes were measured at inside the graph).
  constexpr int kChain = 33;
  double lone = fetchMs(rig, {1, 1}, reps, warmupMs);
  rates.dispatchMs = std::max(0.0, (fetchMs(rig, {1, 1}, reps, warmupMs, 0, kChain) - lone) / (kChain - 1));
  return rates;
}

}  // namespace aor::bench
