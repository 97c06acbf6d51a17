// dispatch_floor: what one compute dispatch costs on a device before it does any work, and what
// its one image store costs per texel format, from Vulkan timestamp queries (Google Benchmark
// manual time, median over --reps repetitions).
//
// Why it exists: the AO pipeline is five dispatches where the naive baseline is one, and on a CPU
// device (lavapipe) each dispatch pays for running its invocations and storing its texels whatever
// the pass computes. These figures say how much of a pass's time that is (bench/RESULTS.md).
//
// Own flags (before Google Benchmark's): --size=WxH (default 640x360)  --reps=N (default 20)
// --device=SEL  --validate (Khronos validation; any message exits 1)  --warmup-ms=MS (default 300
// of steady work first, so that a GPU leaves its idle clocks, as in ao_bench).
// Benchmarks, each name ending with the size: floor/nothing, floor/store_<format> for R16F, RG16F,
// R32F, RGBA16F and RGBA32F, floor/copy_rgba16f (one RGBA16F load and store), all in 8x8
// workgroups; floor/nothing_wg16 and floor/copy_rgba16f_wg16 in 16x16 workgroups.
#include <chrono>
#include <optional>
#include <vector>

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include "core/input_error.h"
#include "options/number.h"
#include "options/size.h"
#include "shaders/dispatch_floor.h"
#include "timed_rig.h"
#include "vk/context.h"
#include "vk/dispatch.h"
#include "vk/resources.h"
#include "vk/vk_check.h"

#include "embedded_shaders.h"

namespace aor::spirv {
std::span<const EmbeddedShader> aor_bench_shaders();  // generated index of bench/shaders/ (shaders/CMakeLists.txt)
}  // namespace aor::spirv

namespace aor::bench {
namespace {

using shader::FloorConstants;

struct Options {
  std::pair<int, int> size{640, 360};
  int reps = 20;
  std::string device;
  bool validate = false;
  double warmupMs = 300;
};

struct Variant {
  const char* name;
  int mode;
  VkFormat target;
  uint32_t workgroupSize = shader::kFloorWorkgroupSize;
};

constexpr Variant kVariants[] = {
    {"nothing", shader::kFloorModeNothing, VK_FORMAT_R16G16B16A16_SFLOAT},
    {"store_r16f", shader::kFloorModeStore, VK_FORMAT_R16_SFLOAT},
    {"store_rg16f", shader::kFloorModeStore, VK_FORMAT_R16G16_SFLOAT},
    {"store_r32f", shader::kFloorModeStore, VK_FORMAT_R32_SFLOAT},
    {"store_rgba16f", shader::kFloorModeStore, VK_FORMAT_R16G16B16A16_SFLOAT},
    {"store_rgba32f", shader::kFloorModeStore, VK_FORMAT_R32G32B32A32_SFLOAT},
    {"copy_rgba16f", shader::kFloorModeCopy, VK_FORMAT_R16G16B16A16_SFLOAT},
    {"nothing_wg16", shader::kFloorModeNothing, VK_FORMAT_R16G16B16A16_SFLOAT, 16},
    {"copy_rgba16f_wg16", shader::kFloorModeCopy, VK_FORMAT_R16G16B16A16_SFLOAT, 16},
};

void toGeneralLayout(VkCommandBuffer cmd, std::initializer_list<VkImage> images) {
  std::vector<VkImageMemoryBarrier2> barriers;
  for (VkImage image : images) {
    VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    b.dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    b.dstAccessMask = VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
    b.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    b.newLayout = VK_IMAGE_LAYOUT_GENERAL;
    b.image = image;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    barriers.push_back(b);
  }
  VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.imageMemoryBarrierCount = uint32_t(barriers.size());
  dependency.pImageMemoryBarriers = barriers.data();
  vkCmdPipelineBarrier2(cmd, &dependency);
}

// Each sample times this many dispatches in a row, a barrier between each two as between the
// pipeline's passes, so that the command buffer's start is not counted as a dispatch's cost (on the
// H100 a lone 1080p dispatch doing nothing measured 0.023 ms, 0.021 in a chain).
constexpr int kDispatchesPerSample = 8;

// The next dispatch overwrites what the previous one wrote.
void barrierBetweenDispatches(VkCommandBuffer cmd) {
  VkMemoryBarrier2 b{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  b.srcStageMask = b.dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
  b.srcAccessMask = b.dstAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
  VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.memoryBarrierCount = 1;
  dependency.pMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &dependency);
}

void recordFloorDispatch(VulkanContext& vk, VkCommandBuffer cmd, const ComputePipeline& pipeline, const GpuImage& source,
                         const GpuImage& target) {
  BoundResource images[2];
  images[0].view = source.view;
  images[1].view = target.view;
  images[0].layout = images[1].layout = VK_IMAGE_LAYOUT_GENERAL;
  FloorConstants constants{{int(target.width), int(target.height)}};
  aor::recordDispatch(vk, cmd, pipeline, images, &constants, groupsFor(pipeline, target.width, target.height));
}

// The images and pipeline of one variant, made before any benchmark runs; FloorCases destroys
// them all in one place.
struct FloorCase {
  GpuImage source, target;
  ComputePipeline pipeline;
};

FloorCase createCase(VulkanContext& vk, const Variant& variant, std::pair<int, int> size) {
  auto [width, height] = size;
  FloorCase c;
  c.source = createImage(vk, width, height, VK_FORMAT_R16G16B16A16_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT);
  c.target = createImage(vk, width, height, variant.target, VK_IMAGE_USAGE_STORAGE_BIT);
  const SpecializationValue specialization[] = {{uint32_t(shader::kFloorSpecMode), uint32_t(variant.mode)},
                                                {uint32_t(shader::kFloorSpecWorkgroupSize), variant.workgroupSize}};
  c.pipeline = createComputePipeline(vk, spirv::code("dispatch_floor", spirv::aor_bench_shaders()), "dispatch_floor",
                                     specialization);
  return c;
}

struct FloorCases {
  VulkanContext& vk;
  std::vector<FloorCase> list;
  ~FloorCases() {
    for (FloorCase& c : list) {
      destroyPipeline(vk, c.pipeline);
      destroyImage(vk, c.target);
      destroyImage(vk, c.source);
    }
  }
};

Options parseOwnFlags(int& argc, char** argv) {
  Options o;
  int kept = 1;
  for (int i = 1; i < argc; ++i) {
    std::string_view arg = argv[i];
    auto value = [&](std::string_view flag) -> std::optional<std::string_view> {
      if (arg.size() > flag.size() && arg.substr(0, flag.size()) == flag && arg[flag.size()] == '=')
        return arg.substr(flag.size() + 1);
      return std::nullopt;
    };
    if (auto s = value("--size")) o.size = parseSize(*s, "--size");
    else if (auto r = value("--reps")) o.reps = parseInt(*r, "--reps", 5, 100000);
    else if (auto d = value("--device")) o.device = std::string(*d);
    else if (auto w = value("--warmup-ms")) o.warmupMs = parseNumber(*w, "--warmup-ms", 0.0, 600000.0);
    else if (arg == "--validate") o.validate = true;
    else argv[kept++] = argv[i];
  }
  argc = kept;
  return o;
}

double timeChain(Rig& rig, const FloorCase& c) {
  double ms = rig.timed([&](VkCommandBuffer cmd) {
    for (int d = 0; d < kDispatchesPerSample; ++d) {
      if (d > 0) barrierBetweenDispatches(cmd);
      recordFloorDispatch(rig.vk, cmd, c.pipeline, c.source, c.target);
    }
  });
  return ms / kDispatchesPerSample;
}

void warmUp(Rig& rig, const FloorCase& c, double warmupMs) {
  auto start = std::chrono::steady_clock::now();
  while (std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() < warmupMs)
    timeChain(rig, c);
}

// Registers and runs every variant; returns with everything it made destroyed.
void runAll(VulkanContext& vk, const Options& options) {
  benchmark::AddCustomContext("vulkan_device", vk.info.name);
  benchmark::AddCustomContext("vulkan_driver", vk.info.driver);
  std::string size = fmt::format("{}x{}", options.size.first, options.size.second);
  Rig rig(vk);
  FloorCases cases{vk, {}};
  for (const Variant& variant : kVariants) {
    FloorCase& c = cases.list.emplace_back(createCase(vk, variant, options.size));
    // Untimed: the layout change, and lavapipe's compile to machine code on the first dispatch.
    rig.timed([&](VkCommandBuffer cmd) {
      toGeneralLayout(cmd, {c.source.image, c.target.image});
      recordFloorDispatch(vk, cmd, c.pipeline, c.source, c.target);
    });
  }
  warmUp(rig, cases.list.back(), options.warmupMs);
  for (size_t i = 0; i < cases.list.size(); ++i)
    benchmark::RegisterBenchmark(fmt::format("floor/{}/{}", kVariants[i].name, size).c_str(),
                                 [&, i](benchmark::State& state) {
                                   const FloorCase& c = cases.list[i];
                                   for (auto _ : state) state.SetIterationTime(1e-3 * timeChain(rig, c));
                                 })
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1)
        ->Repetitions(options.reps)
        ->ReportAggregatesOnly(true);
  benchmark::RunSpecifiedBenchmarks();
}

}  // namespace
}  // namespace aor::bench

int main(int argc, char** argv) {
  using namespace aor::bench;
  try {
    Options options = parseOwnFlags(argc, argv);
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 2;
    aor::ContextScope context(aor::ContextOptions{options.device, options.validate});
    runAll(context.vk, options);
    benchmark::Shutdown();
    if (size_t messages = context.vk.validationMessageCount()) {
      fmt::print(stderr, "dispatch_floor: {} validation messages\n", messages);
      return 1;
    }
  } catch (const aor::InputError& e) {
    fmt::print(stderr, "dispatch_floor: error: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "dispatch_floor: {}\n", e.what());
    return 1;
  }
  return 0;
}
