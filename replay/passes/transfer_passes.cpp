// Upload of G-buffers and read-back of the result: transfer passes in the graph, so their
// barriers are derived like every other pass's and their time shows up in the report.
#include "pipeline/pass_context.h"
#include "passes/pass_names.h"
#include "passes/passes.h"

namespace aor {
namespace {

VkBufferImageCopy wholeImage(const GpuImage& image) {
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {image.width, image.height, 1};
  return region;
}

}  // namespace

void addUploadPass(graph::RenderGraph& graph, const GpuBuffer& depth, graph::ResourceId depthImage,
                   const GpuBuffer* normals, graph::ResourceId normalsImage) {
  graph.addPass(
      std::string(kUploadPass),
      [&](graph::PassBuilder& b) {
        b.write(depthImage, graph::Access::TransferWrite);
        if (normalsImage != graph::kNoResource) b.write(normalsImage, graph::Access::TransferWrite);
      },
      [&depth, depthImage, normals, normalsImage](graph::PassContext& ctx) {
        auto copy = [&](VkBuffer buffer, graph::ResourceId id) {
          const auto& image = ctx.image(id);
          auto region = wholeImage(image);
          vkCmdCopyBufferToImage(ctx.cmd, buffer, image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
        };
        copy(depth.buffer, depthImage);
        if (normalsImage != graph::kNoResource) copy(normals->buffer, normalsImage);
      });
}

void addReadbackPass(graph::RenderGraph& graph, graph::ResourceId image, const GpuBuffer& target) {
  graph.addPass(
      std::string(kReadbackPass),
      [&](graph::PassBuilder& b) {
        b.read(image, graph::Access::TransferRead);
        b.sideEffect();
      },
      [image, &target](graph::PassContext& ctx) {
        const auto& source = ctx.image(image);
        auto region = wholeImage(source);
        vkCmdCopyImageToBuffer(ctx.cmd, source.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target.buffer, 1, &region);
        // The host reads the buffer after the fence: make the copy's writes available to it.
        VkBufferMemoryBarrier2 toHost{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
        toHost.srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
        toHost.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
        toHost.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
        toHost.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
        toHost.srcQueueFamilyIndex = toHost.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        toHost.buffer = target.buffer;
        toHost.size = VK_WHOLE_SIZE;
        VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        dependency.bufferMemoryBarrierCount = 1;
        dependency.pBufferMemoryBarriers = &toHost;
        vkCmdPipelineBarrier2(ctx.cmd, &dependency);
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

}  // namespace aor
