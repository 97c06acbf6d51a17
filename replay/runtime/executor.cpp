#include "runtime/executor.h"

#include "vk/context.h"
#include "vk/vk_check.h"

namespace aor {
namespace {

constexpr uint32_t kMaxTimedPasses = 256;

// The source and destination scopes every barrier kind shares.
template <typename VkBarrier>
VkBarrier withScopes(VkBarrier barrier, const graph::Barrier& b) {
  barrier.srcStageMask = b.before.stage;
  barrier.srcAccessMask = b.before.access;
  barrier.dstStageMask = b.after.stage;
  barrier.dstAccessMask = b.after.access;
  barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  return barrier;
}

VkImageMemoryBarrier2 imageBarrier(const graph::Barrier& b, VkImage image) {
  auto barrier = withScopes(VkImageMemoryBarrier2{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2}, b);
  barrier.oldLayout = b.before.layout;
  barrier.newLayout = b.after.layout;
  barrier.image = image;
  barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, b.range.baseMip, b.range.mipCount, b.range.baseLayer,
                              b.range.layerCount};
  return barrier;
}

VkBufferMemoryBarrier2 bufferBarrier(const graph::Barrier& b, VkBuffer buffer) {
  auto barrier = withScopes(VkBufferMemoryBarrier2{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2}, b);
  barrier.buffer = buffer;
  barrier.size = VK_WHOLE_SIZE;
  return barrier;
}

void recordBarriers(const graph::PassContext& context, const std::vector<graph::Barrier>& barriers) {
  std::vector<VkImageMemoryBarrier2> images;
  std::vector<VkBufferMemoryBarrier2> buffers;
  for (const auto& b : barriers) {
    if (context.graph.resources()[b.resource].isBuffer())
      buffers.push_back(bufferBarrier(b, context.buffer(b.resource).buffer));
    else
      images.push_back(imageBarrier(b, context.image(b.resource).image));
  }
  if (images.empty() && buffers.empty()) return;
  VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.imageMemoryBarrierCount = uint32_t(images.size());
  dependency.pImageMemoryBarriers = images.data();
  dependency.bufferMemoryBarrierCount = uint32_t(buffers.size());
  dependency.pBufferMemoryBarriers = buffers.data();
  vkCmdPipelineBarrier2(context.cmd, &dependency);
}

}  // namespace

GraphExecutor::GraphExecutor(VulkanContext& vk) : vk_(vk) {
  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = vk.commandPool;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  VK_CHECK(vkAllocateCommandBuffers(vk.device, &alloc, &cmd_));
  VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VK_CHECK(vkCreateFence(vk.device, &fenceInfo, nullptr, &fence_));
  queryCapacity_ = 2 * kMaxTimedPasses;
  VkQueryPoolCreateInfo queryInfo{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  queryInfo.queryType = VK_QUERY_TYPE_TIMESTAMP;
  queryInfo.queryCount = queryCapacity_;
  VK_CHECK(vkCreateQueryPool(vk.device, &queryInfo, nullptr, &queries_));
}

GraphExecutor::~GraphExecutor() {
  vkDeviceWaitIdle(vk_.device);
  vkDestroyQueryPool(vk_.device, queries_, nullptr);
  vkDestroyFence(vk_.device, fence_, nullptr);
  vkFreeCommandBuffers(vk_.device, vk_.commandPool, 1, &cmd_);
}

void GraphExecutor::record(const graph::RenderGraph& graph, const graph::CompiledGraph& compiled,
                           const std::vector<graph::PhysicalResource>& resources) {
  if (compiled.passes.size() > kMaxTimedPasses) throw std::logic_error("render graph has more passes than timestamp slots");
  VK_CHECK(vkResetCommandBuffer(cmd_, 0));
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  VK_CHECK(vkBeginCommandBuffer(cmd_, &begin));
  vkCmdResetQueryPool(cmd_, queries_, 0, queryCapacity_);

  graph::PassContext context{vk_, cmd_, graph, resources};
  uint32_t query = 0;
  for (const auto& pass : compiled.passes) {
    recordBarriers(context, pass.barriersBefore);
    vkCmdWriteTimestamp2(cmd_, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, queries_, query++);
    recordPass(context, pass);
    vkCmdWriteTimestamp2(cmd_, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, queries_, query++);
  }
  VK_CHECK(vkEndCommandBuffer(cmd_));
  recordedPasses_ = uint32_t(compiled.passes.size());
}

void GraphExecutor::recordPass(graph::PassContext& context, const graph::CompiledPass& pass) {
  const auto& decl = context.graph.passes()[pass.pass];
  context.pass = &decl;
  context.compiled = &pass;
  if (decl.execute) decl.execute(context);
}

std::vector<EventCounts> GraphExecutor::countPasses(const graph::RenderGraph& graph, const graph::CompiledGraph& compiled,
                                                    const std::vector<graph::PhysicalResource>& resources,
                                                    CallgrindCounter& counter) {
  std::vector<EventCounts> counts;
  graph::PassContext context{vk_, cmd_, graph, resources};
  for (const auto& pass : compiled.passes) {
    VK_CHECK(vkResetCommandBuffer(cmd_, 0));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    VK_CHECK(vkBeginCommandBuffer(cmd_, &begin));
    recordBarriers(context, pass.barriersBefore);
    recordPass(context, pass);
    VK_CHECK(vkEndCommandBuffer(cmd_));
    counter.begin();
    aor::submitAndWait(vk_, cmd_, fence_);
    counts.push_back(counter.end(graph.passes()[pass.pass].name));
  }
  recordedPasses_ = 0;
  return counts;
}

std::vector<GraphExecutor::PassTime> GraphExecutor::submitAndWait() {
  aor::submitAndWait(vk_, cmd_, fence_);

  std::vector<uint64_t> stamps(2 * recordedPasses_);
  std::vector<PassTime> times(recordedPasses_);
  if (recordedPasses_ == 0) return times;
  VK_CHECK(vkGetQueryPoolResults(vk_.device, queries_, 0, 2 * recordedPasses_, stamps.size() * sizeof(uint64_t),
                                 stamps.data(), sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  auto toMs = [&](uint64_t from, uint64_t to) { return timestampDeltaMs(vk_, from, to); };
  for (uint32_t i = 0; i < recordedPasses_; ++i)
    times[i] = {toMs(stamps[0], stamps[2 * i]), toMs(stamps[2 * i], stamps[2 * i + 1])};
  return times;
}

}  // namespace aor
