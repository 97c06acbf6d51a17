// The shared front of every frame: the capture's inputs uploaded, linear view distance, and
// view-space normals (rotated from the capture's, or reconstructed from depth when it has none).
#include "shared_passes/shared_passes.h"
#include "shared_passes/camera.h"
#include "blocks/linearize_depth.h"
#include "core/pass_names.h"
#include "blocks/reconstruct_normals.h"
#include "blocks/view_normals.h"
#include "runtime/pass_context.h"

namespace aor::shared_passes {
namespace {

inline constexpr const char* kDistanceHistory = "distance_history";

VkBufferImageCopy wholeImage(const GpuImage& image) {
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {image.width, image.height, 1};
  return region;
}

// One `upload` pass copies every input a live pass reads (writeIfRead), so a technique that reads
// no normals or no second layer gets neither copied nor allocated.
void addUploadPass(graph::RenderGraph& graph, const FrontBuffers& buffers, const FrameBuilder::Front& front) {
  std::vector<std::pair<const GpuBuffer*, graph::ResourceId>> copies{{buffers.depth, front.depth}};
  if (front.worldNormals != graph::kNoResource) copies.emplace_back(buffers.normals, front.worldNormals);
  if (front.depth2 != graph::kNoResource) copies.emplace_back(buffers.depth2, front.depth2);
  graph.addPass(
      std::string(kUploadPass),
      [&](graph::PassBuilder& b) {
        for (const auto& [buffer, image] : copies) b.writeIfRead(image, graph::Access::TransferWrite);
      },
      [copies](graph::PassContext& ctx) {
        for (const auto& [buffer, id] : copies) {
          if (!ctx.has(id)) continue;
          const auto& image = ctx.image(id);
          auto region = wholeImage(image);
          vkCmdCopyBufferToImage(ctx.cmd, buffer->buffer, image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
        }
      });
}

void addLinearizeDepthPass(FrameBuilder& frame, graph::ResourceId depth, graph::ResourceId distance) {
  const auto& cam = frame.camera();
  auto params = projectionParams(cam.projection, cam.width, cam.height);
  shader::LinearizeConstants constants{};
  constants.size = {cam.width, cam.height};
  constants.projection22 = params.projection22;
  constants.projection32 = params.projection32;
  constants.reversedDepth = params.reversedDepth ? 1u : 0u;
  auto& pipelines = frame.pipelines();
  frame.graph().addPass(
      "linearize_depth",
      [&](graph::PassBuilder& b) {
        b.read(depth, graph::Access::StorageRead);
        b.write(distance);
      },
      [&pipelines, constants, depth, distance](graph::PassContext& ctx) {
        dispatchCompute(ctx, pipelines.get("blocks/linearize_depth"), {depth, distance}, &constants,
                        uint32_t(constants.size.x), uint32_t(constants.size.y));
      });
}

graph::ResourceId addReconstructNormalsPass(FrameBuilder& frame, graph::ResourceId distance) {
  const auto& cam = frame.camera();
  auto params = projectionParams(cam.projection, cam.width, cam.height);
  shader::ReconstructNormalsConstants constants{};
  constants.ndcToViewMul = params.ndcToViewMul;
  constants.ndcToViewAdd = params.ndcToViewAdd;
  constants.invSize = {1.0f / float(cam.width), 1.0f / float(cam.height)};
  constants.size = {cam.width, cam.height};
  auto normals = frame.graph().createImage("normals_reconstructed", {frame.size().x, frame.size().y, VK_FORMAT_R16G16B16A16_SFLOAT});
  auto& pipelines = frame.pipelines();
  frame.graph().addPass(
      "reconstruct_normals",
      [&](graph::PassBuilder& b) {
        b.read(distance);
        b.write(normals);
      },
      [&pipelines, constants, distance, normals](graph::PassContext& ctx) {
        dispatchCompute(ctx, pipelines.get("blocks/reconstruct_normals"), {distance, normals}, &constants,
                        uint32_t(constants.size.x), uint32_t(constants.size.y));
      });
  return normals;
}

graph::ResourceId addViewNormalsPass(FrameBuilder& frame, graph::ResourceId worldNormals) {
  const auto& cam = frame.camera();
  shader::ViewNormalsConstants constants{};
  constants.worldToView0 = glm::vec4(glm::vec3(cam.view[0]), 0.0f);
  constants.worldToView1 = glm::vec4(glm::vec3(cam.view[1]), 0.0f);
  constants.worldToView2 = glm::vec4(glm::vec3(cam.view[2]), 0.0f);
  constants.size = {cam.width, cam.height};
  auto normals = frame.graph().createImage("view_normals", {frame.size().x, frame.size().y, VK_FORMAT_R16G16B16A16_SFLOAT});
  auto& pipelines = frame.pipelines();
  frame.graph().addPass(
      "view_normals",
      [&](graph::PassBuilder& b) {
        b.read(worldNormals, graph::Access::StorageRead);
        b.write(normals);
      },
      [&pipelines, constants, worldNormals, normals](graph::PassContext& ctx) {
        dispatchCompute(ctx, pipelines.get("blocks/view_normals"), {worldNormals, normals}, &constants,
                        uint32_t(constants.size.x), uint32_t(constants.size.y));
      });
  return normals;
}

}  // namespace

void declareFront(FrameBuilder& frame, const FrontBuffers& buffers, bool keepDistance) {
  auto& g = frame.graph();
  uint32_t w = frame.size().x, h = frame.size().y;
  // The inputs are uploaded anew every frame, so their images are transients: once their last
  // reader has run, their memory can hold later images (aliasing).
  FrameBuilder::Front front;
  front.depth = g.createImage("depth", {w, h, VK_FORMAT_R32_SFLOAT});
  if (frame.capture().normals) front.worldNormals = g.createImage("normals", {w, h, VK_FORMAT_R16G16B16A16_SFLOAT});
  if (frame.capture().depth2) front.depth2 = g.createImage("depth2", {w, h, VK_FORMAT_R32_SFLOAT});
  addUploadPass(g, buffers, front);

  // A technique that reads last frame's distance (seed 000's temporal depth test) gets this frame's
  // written into history.
  if (keepDistance) {
    auto history = frame.history(kDistanceHistory, {w, h, VK_FORMAT_R32_SFLOAT});
    front.distance = history.current;
    front.previousDistance = history.previous;
  } else {
    front.distance = g.createImage("view_distance", {w, h, VK_FORMAT_R32_SFLOAT});
  }
  addLinearizeDepthPass(frame, front.depth, front.distance);
  front.reconstructedNormals = addReconstructNormalsPass(frame, front.distance);
  front.viewNormals = front.worldNormals != graph::kNoResource ? addViewNormalsPass(frame, front.worldNormals)
                                                               : front.reconstructedNormals;
  if (frame.capture().normals) frame.explain("reconstruct_normals", "the capture has normals");
  frame.setFront(front);
}

}  // namespace aor::shared_passes
