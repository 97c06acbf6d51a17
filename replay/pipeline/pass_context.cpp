#include "pipeline/pass_context.h"

#include <stdexcept>

#include "vk/dispatch.h"

namespace aor::graph {

const GpuImage& PassContext::image(ResourceId id) const {
  if (id >= images.size() || !images[id]) throw std::logic_error("pass touched a resource it did not declare");
  return *images[id];
}

VkImageLayout PassContext::layout(ResourceId id) const {
  if (!pass) throw std::logic_error("no pass is being recorded");
  return requiredState(*pass, id).layout;
}

}  // namespace aor::graph

namespace aor {

void dispatchCompute(graph::PassContext& ctx, const ComputePipeline& pipeline, std::initializer_list<graph::ResourceId> images,
                     const void* pushConstants, uint32_t width, uint32_t height) {
  std::vector<BoundImage> bound;
  bound.reserve(images.size());
  for (graph::ResourceId id : images) bound.push_back({ctx.image(id).view, ctx.layout(id)});
  recordDispatch(ctx.vk, ctx.cmd, pipeline, bound, pushConstants, width, height);
}

}  // namespace aor
