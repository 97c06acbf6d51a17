// `aoreplay graph`: prints the compiled render graph for a capture and settings (passes run and
// culled with reasons, resources, lifetimes, aliasing, barriers) and writes it as Graphviz DOT.
// Needs no GPU: the graph is built and compiled, never executed.
#include <filesystem>
#include <memory>

#include <fmt/format.h>

#include "cli/commands.h"
#include "cli/handlers.h"
#include "cli/settings_options.h"
#include "pipeline/ao_graph.h"
#include "report/output_directory.h"
#include "vk/context.h"

namespace aor::cli {
namespace {

namespace fs = std::filesystem;

struct GraphArgs {
  std::string capture;
  SettingsOptions settings;
  std::string dot;
};

int graphCommand(const GraphArgs& args) {
  Capture capture = loadCapture(args.capture);
  AoSettings settings = args.settings.resolve(capture);
  auto [begin, end] = args.settings.frameRange(capture);
  bool temporalWanted = end - begin > 1 && settings.temporal > 0.0f;
  auto camera = [&](int index) {
    const auto& frame = capture.frames[size_t(index)];
    return FrameCamera{frame.view, frame.projection, capture.width, capture.height, uint32_t(index)};
  };

  VulkanContext noDevice;  // pipelines are created only when a pass executes, which never happens here
  PassPipelines pipelines(noDevice);
  GpuBuffer placeholder;
  AoFrameBuffers buffers{&placeholder, capture.hasNormals ? &placeholder : nullptr, &placeholder};
  // A steady-state frame: the second of the range when there is one, with history valid and its
  // history images in the states the first frame left them in (as in a replay).
  int index = begin;
  HistoryStates history;
  if (temporalWanted) {
    AoFrameInputs first{camera(begin), camera(begin), capture.hasNormals, true, false, settings};
    auto firstGraph = buildAoFrameGraph(first, pipelines, {}, buffers);
    history = historyStatesAfter(firstGraph.graph, firstGraph.graph.compile());
    index = begin + 1;
  }
  AoFrameInputs inputs{camera(index), camera(temporalWanted ? index - 1 : index), capture.hasNormals, temporalWanted,
                       temporalWanted, settings};
  auto frameGraph = buildAoFrameGraph(inputs, pipelines, history, buffers);
  auto compiled = frameGraph.graph.compile();

  fmt::print("capture: {} ({}x{}), frame {} of replay {}:{}, settings: {}\n", capture.name, capture.width,
             capture.height, index, begin, end, toJson(settings).dump());
  fmt::print("{}", graph::describe(frameGraph.graph, compiled));
  for (const auto& [pass, why] : frameGraph.notes) fmt::print("why {} is not needed: {}\n", pass, why);

  fs::path dotPath = args.dot.empty() ? fs::path("out") / capture.name / "graph.dot" : fs::path(args.dot);
  writeFileAtomically(dotPath, graph::toDot(frameGraph.graph, compiled));  // InputError (exit 2) if it cannot
  fmt::print("dot: {} (render with: dot -Tsvg {} -o graph.svg)\n", dotPath.string(), dotPath.string());
  return kExitOk;
}

}  // namespace

void registerGraphCommand(CLI::App& app) {
  auto args = std::make_shared<GraphArgs>();
  auto* cmd = app.add_subcommand("graph", "print the compiled render graph and write it as Graphviz DOT");
  cmd->add_option("capture", args->capture, "capture folder")->required();
  args->settings.add(*cmd);
  cmd->add_option("--dot", args->dot, "DOT output file (default out/<capture name>/graph.dot)");
  handlers()["graph"] = [args] { return graphCommand(*args); };
}

}  // namespace aor::cli
