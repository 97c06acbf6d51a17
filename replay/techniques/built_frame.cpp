#include "techniques/built_frame.h"

#include <stdexcept>
#include <utility>

#include <fmt/format.h>

namespace aor {

HistoryNeeds historyNeedsOf(const Settings& settings, int frames) {
  const auto& t = settings.technique();
  if (frames < 2 || !t.history) return {};
  return t.history(settings);
}

BuiltFrame buildFrame(PipelineCache& pipelines, const FrameBuilder::Setup& setup, const FrameBuffers& buffers) {
  BuiltFrame out;
  FrameBuilder frame(out.graph, pipelines, setup);
  const Settings& settings = *setup.settings;
  const Technique& technique = settings.technique();
  HistoryNeeds needs = setup.historyWanted && technique.history ? technique.history(settings) : HistoryNeeds{};
  shared_passes::declareFront(frame, buffers.front, setup.historyWanted && needs.distance);
  technique.addPasses(frame, settings);
  if (frame.output() == graph::kNoResource)
    throw std::logic_error(fmt::format("technique {} set no output", technique.name));
  static const GpuBuffer placeholder;  // dry builds (`aoreplay graph`, sizing the read-back) never execute
  shared_passes::addReadbackPass(out.graph, frame.output(), buffers.readback ? *buffers.readback : placeholder);
  for (const auto& d : frame.debugReadbacks()) shared_passes::addDebugReadbackPass(out.graph, d);
  out.output = frame.output();
  out.outputFormat = out.graph.resources()[frame.output()].desc.format;
  out.outputLayout = frame.outputLayout();
  out.notes = frame.notes();
  out.debug = frame.debugReadbacks();
  out.values = frame.reportValues();
  return out;
}

BuiltFrame buildSteadyStateFrame(PipelineCache& pipelines, const FrameBuilder::Setup& first, FrameBuilder::Setup steady) {
  if (steady.historyValid) {
    auto firstGraph = buildFrame(pipelines, first, {});
    steady.historyStates = historyStatesAfter(firstGraph.graph, firstGraph.graph.compile());
  }
  return buildFrame(pipelines, steady, {});
}

HistoryStates historyStatesAfter(const graph::RenderGraph& graph, const graph::CompiledGraph& compiled) {
  std::map<std::pair<std::string, bool>, graph::ResourceState> next;  // (base, current next frame) -> state
  for (graph::ResourceId id = 0; id < graph.resources().size(); ++id) {
    const auto& decl = graph.resources()[id];
    if (decl.kind == graph::ResourceKind::History && compiled.resources[id].used)
      next[{decl.historyBase, !decl.historyCurrent}] = compiled.resources[id].finalState;
  }
  return [next = std::move(next)](const std::string& base, bool current) {
    auto it = next.find({base, current});
    return it == next.end() ? graph::ResourceState{} : it->second;
  };
}

graph::RenderGraph buildHistoryPoisonGraph(const FrameBuilder::Setup& setup, const std::string& base, graph::ImageDesc desc,
                                           float value) {
  graph::RenderGraph g;
  auto state = [&](bool current) { return setup.historyStates ? setup.historyStates(base, current) : graph::ResourceState{}; };
  auto history = g.createHistory(base, desc, true, state(false), state(true));
  shared_passes::addFillPass(g, history.previous, value);
  return g;
}

}  // namespace aor
