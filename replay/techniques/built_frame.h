#pragma once
// One frame's render graph: the shared front, the technique's passes, the read-back of its output
// and of the debug views the run asked for. The replay builds one per run of a frame; `aoreplay
// graph` builds them to compile and print, never to execute.
#include <map>
#include <string>
#include <vector>

#include "shared_passes/shared_passes.h"
#include "graph/render_graph.h"
#include "technique_api/frame_builder.h"

namespace aor {

struct FrameBuffers {
  shared_passes::FrontBuffers front;
  const GpuBuffer* readback = nullptr;  // receives the output image
};

struct BuiltFrame {
  graph::RenderGraph graph;
  graph::ResourceId output = graph::kNoResource;
  VkFormat outputFormat = VK_FORMAT_UNDEFINED;
  OutputLayout outputLayout;
  std::map<std::string, std::string> notes;  // pass name -> the setting or input that made it unneeded
  std::vector<DebugReadback> debug;
  std::map<std::string, double> values;  // FrameBuilder::reportValue
};

// Whether the technique keeps history under `settings` in a replay of `frames` frames.
HistoryNeeds historyNeedsOf(const Settings& settings, int frames);

BuiltFrame buildFrame(PipelineCache& pipelines, const FrameBuilder::Setup& setup, const FrameBuffers& buffers);

// The history states the frame after `graph` starts from, for tools that compile frames without
// running them (`aoreplay graph`): its `current` images become `previous`, and it writes into the
// images that were `previous` (UNDEFINED where there was none, as after a replay's first frame).
// The same bookkeeping as PhysicalResources::keepFinalStates and swapHistory.
HistoryStates historyStatesAfter(const graph::RenderGraph& graph, const graph::CompiledGraph& compiled);

// A steady-state frame's graph for tools that compile frames without running them (`aoreplay
// graph`, ao_bench's pass list): when `steady` has valid history, `first` (a frame without history,
// sharing `steady`'s technique state) is built before it, so that `steady` starts from the history
// states `first` left and a technique that keeps state per frame (rtao) has seen the frame before.
BuiltFrame buildSteadyStateFrame(PipelineCache& pipelines, const FrameBuilder::Setup& first, FrameBuilder::Setup steady);

// Test-only fault injection (ReplayOptions::testPoisonHistoryAt): one pass that fills the history
// `base`'s `previous` image with `value`, so a test can show on a real device what a technique makes
// of history no correct frame can leave (NaN, Inf). Never part of a normal replay.
graph::RenderGraph buildHistoryPoisonGraph(const FrameBuilder::Setup& setup, const std::string& base, graph::ImageDesc desc,
                                           float value);

}  // namespace aor
