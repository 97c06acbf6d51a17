#include "technique_api/frame_builder.h"

#include <stdexcept>

#include <fmt/format.h>

namespace aor {

FrameBuilder::FrameBuilder(graph::RenderGraph& graph, PipelineCache& pipelines, Setup setup)
    : graph_(graph), pipelines_(pipelines), setup_(std::move(setup)) {}

graph::ResourceState FrameBuilder::historyState(const std::string& base, bool current) const {
  return setup_.historyStates ? setup_.historyStates(base, current) : graph::ResourceState{};
}

graph::HistoryPair FrameBuilder::history(const std::string& name, graph::ImageDesc desc) {
  if (!setup_.historyWanted)
    throw std::logic_error(fmt::format("technique {} declares history '{}' in a replay that keeps none (HistoryNeeds)",
                                       settings().technique().name, name));
  return graph_.createHistory(name, desc, setup_.historyValid, historyState(name, false), historyState(name, true));
}

void FrameBuilder::setOutput(graph::ResourceId image, OutputLayout layout) {
  const auto& decl = graph_.resources().at(image);
  if (decl.isBuffer() || decl.desc.width != size().x || decl.desc.height != size().y)
    throw std::logic_error(fmt::format("technique {}: output '{}' is not a {}x{} image", settings().technique().name,
                                       decl.name, size().x, size().y));
  output_ = image;
  outputLayout_ = layout;
}

void FrameBuilder::debugView(const std::string& name, graph::ResourceId resource, graph::Subresources range) {
  if (!settings().technique().debugView(name))
    throw std::logic_error(fmt::format("technique {} reads back debug view '{}' it does not declare",
                                       settings().technique().name, name));
  if (!wantsDebugView(name)) return;
  const auto& decl = graph_.resources().at(resource);
  DebugReadback d{name, resource, range};
  uint64_t bytes = decl.buffer.bytes;
  if (!decl.isBuffer()) {
    d.range = range.resolve(decl.desc);
    if (d.range.mipCount != 1 || d.range.layerCount != 1)
      throw std::logic_error(fmt::format("debug view '{}' must be one level of one layer", name));
    d.format = decl.desc.format;
    d.width = std::max(1u, decl.desc.width >> d.range.baseMip);
    d.height = std::max(1u, decl.desc.height >> d.range.baseMip);
    bytes = graph::imageBytes({d.width, d.height, d.format});
  }
  d.target = setup_.debugTarget ? setup_.debugTarget(name, bytes) : nullptr;
  debug_.push_back(d);
}

}  // namespace aor
