// The host's copies: read-back of the result and of debug views, and the test-only fill. Transfer
// passes in the graph, so their barriers are derived like every other pass's and their time shows
// up in the report.
#include "shared_passes/shared_passes.h"
#include "core/pass_names.h"
#include "runtime/pass_context.h"

namespace aor::shared_passes {
namespace {

// The host reads a read-back buffer after the fence: make the copy's writes available to it.
void makeVisibleToHost(VkCommandBuffer cmd, VkBuffer buffer) {
  VkBufferMemoryBarrier2 toHost{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
  toHost.srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
  toHost.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
  toHost.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
  toHost.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
  toHost.srcQueueFamilyIndex = toHost.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  toHost.buffer = buffer;
  toHost.size = VK_WHOLE_SIZE;
  VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.bufferMemoryBarrierCount = 1;
  dependency.pBufferMemoryBarriers = &toHost;
  vkCmdPipelineBarrier2(cmd, &dependency);
}

void copyLevelToBuffer(graph::PassContext& ctx, graph::ResourceId id, const graph::Subresources& range, VkBuffer target) {
  const auto& source = ctx.image(id);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, range.baseMip, range.baseLayer, 1};
  region.imageExtent = {std::max(1u, source.width >> range.baseMip), std::max(1u, source.height >> range.baseMip), 1};
  vkCmdCopyImageToBuffer(ctx.cmd, source.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target, 1, &region);
  makeVisibleToHost(ctx.cmd, target);
}

}  // namespace

void addReadbackPass(graph::RenderGraph& graph, graph::ResourceId image, const GpuBuffer& target) {
  graph.addPass(
      std::string(kReadbackPass),
      [&](graph::PassBuilder& b) {
        b.read(image, graph::Access::TransferRead);
        b.sideEffect();
      },
      [image, &target](graph::PassContext& ctx) { copyLevelToBuffer(ctx, image, {0, 1, 0, 1}, target.buffer); });
}

void addDebugReadbackPass(graph::RenderGraph& graph, const DebugReadback& readback) {
  bool buffer = graph.resources().at(readback.resource).isBuffer();
  graph.addPass(
      "debug:" + readback.name,
      [&](graph::PassBuilder& b) {
        b.read(readback.resource, graph::Access::TransferRead, readback.range);
        b.sideEffect();
      },
      [readback, buffer](graph::PassContext& ctx) {
        if (!readback.target) return;  // declared for `aoreplay graph`, read back nowhere
        if (!buffer) return copyLevelToBuffer(ctx, readback.resource, readback.range, readback.target->buffer);
        VkBufferCopy region{0, 0, readback.target->size};
        vkCmdCopyBuffer(ctx.cmd, ctx.buffer(readback.resource).buffer, readback.target->buffer, 1, &region);
        makeVisibleToHost(ctx.cmd, readback.target->buffer);
      });
}

void addFillPass(graph::RenderGraph& graph, graph::ResourceId image, float value) {
  graph.addPass(
      "fill",
      [&](graph::PassBuilder& b) {
        b.write(image, graph::Access::ClearWrite);
        b.sideEffect();
      },
      [image, value](graph::PassContext& ctx) {
        VkClearColorValue color{};
        for (float& channel : color.float32) channel = value;
        VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdClearColorImage(ctx.cmd, ctx.image(image).image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &color, 1, &range);
      });
}

}  // namespace aor::shared_passes
