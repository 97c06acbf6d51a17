#pragma once
// GPU time of recorded work from two timestamp queries, for the bench tools that dispatch without a
// render graph (dispatch_floor, device_rates).
#include "vk/context.h"
#include "vk/vk_check.h"

namespace aor::bench {

// One command buffer, one fence and two timestamps, reused for every timed dispatch.
struct Rig {
  VulkanContext& vk;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;
  VkQueryPool queries = VK_NULL_HANDLE;

  explicit Rig(VulkanContext& context) : vk(context) {
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = vk.commandPool;
    alloc.commandBufferCount = 1;
    VK_CHECK(vkAllocateCommandBuffers(vk.device, &alloc, &cmd));
    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VK_CHECK(vkCreateFence(vk.device, &fenceInfo, nullptr, &fence));
    VkQueryPoolCreateInfo queryInfo{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    queryInfo.queryType = VK_QUERY_TYPE_TIMESTAMP;
    queryInfo.queryCount = 2;
    VK_CHECK(vkCreateQueryPool(vk.device, &queryInfo, nullptr, &queries));
  }
  ~Rig() {
    vkDestroyQueryPool(vk.device, queries, nullptr);
    vkDestroyFence(vk.device, fence, nullptr);
    vkFreeCommandBuffers(vk.device, vk.commandPool, 1, &cmd);
  }

  // Records `record` between two timestamps, runs it and returns the GPU time in milliseconds.
  template <class Record>
  double timed(Record&& record) {
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    vkCmdResetQueryPool(cmd, queries, 0, 2);
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, queries, 0);
    record(cmd);
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, queries, 1);
    VK_CHECK(vkEndCommandBuffer(cmd));
    submitAndWait(vk, cmd, fence);
    uint64_t ticks[2];
    VK_CHECK(vkGetQueryPoolResults(vk.device, queries, 0, 2, sizeof ticks, ticks, sizeof ticks[0],
                                   VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    return timestampDeltaMs(vk, ticks[0], ticks[1]);
  }
};

}  // namespace aor::bench
