// `aoreplay graph`: prints the compiled render graph for a capture and settings (passes run and
// culled with reasons, resources, lifetimes, aliasing, barriers) and writes it as Graphviz DOT.
// Needs no GPU: the graph is built and compiled, never executed.
#include <filesystem>
#include <memory>

#include <fmt/format.h>

#include "cli/commands.h"
#include "cli/handlers.h"
#include "cli/settings_options.h"
#include "techniques/built_frame.h"
#include "core/output_directory.h"
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
  Settings settings = args.settings.resolve(capture);
  auto [begin, end] = args.settings.frameRange(capture);
  const Technique& technique = settings.technique();
  bool historyWanted = historyNeedsOf(settings, end - begin).keeps;
  auto setupFor = [&](int index, bool valid) {
    const auto& frame = capture.frames[size_t(index)];
    FrameBuilder::Setup s;
    s.settings = &settings;
    s.camera = FrameCamera{frame.view, frame.projection, capture.width, capture.height, uint32_t(index)};
    const int previousIndex = valid ? index - 1 : index;
    const auto& previous = capture.frames[size_t(previousIndex)];
    s.previousCamera =
        FrameCamera{previous.view, previous.projection, capture.width, capture.height, uint32_t(previousIndex)};
    s.capture = {capture.hasNormals, capture.hasDepth2 && technique.inputs.depth2 != InputUse::Unused};
    s.historyWanted = historyWanted;
    s.historyValid = valid;
    s.debugViews = {args.settings.debugViews.begin(), args.settings.debugViews.end()};
    return s;
  };
  std::unique_ptr<TechniqueState> state;
  if (technique.prepare) state = technique.prepare(ReplaySetup{capture, settings, nullptr});

  VulkanContext noDevice;  // pipelines are created only when a pass executes, which never happens here
  PipelineCache pipelines(noDevice);
  // A steady-state frame: the second of the range when there is one, with history valid and its
  // history images in the states the first frame left them in (as in a replay).
  const int index = historyWanted ? begin + 1 : begin;
  auto first = setupFor(begin, false);
  first.state = state.get();
  auto setup = setupFor(index, historyWanted);
  setup.state = state.get();
  auto builtFrame = buildSteadyStateFrame(pipelines, first, setup);
  auto compiled = builtFrame.graph.compile();

  // With --dot - the graph goes to standard output, so the description goes to standard error.
  FILE* text = args.dot == "-" ? stderr : stdout;
  fmt::print(text, "capture: {} ({}x{}), frame {} of replay {}:{}, settings: {}\n", capture.name, capture.width,
             capture.height, index, begin, end, settings.toJson().dump());
  fmt::print(text, "{}", graph::describe(builtFrame.graph, compiled));
  for (const auto& [pass, why] : builtFrame.notes) fmt::print(text, "why {} is not needed: {}\n", pass, why);

  fs::path dotPath = args.dot.empty() ? fs::path("out") / capture.name / "graph.dot" : fs::path(args.dot);
  // InputError (exit 2) if it cannot, or if it would overwrite the capture's own files.
  writeFileAtomically(dotPath, graph::toDot(builtFrame.graph, compiled), captureFiles(capture));
  if (args.dot != "-")
    fmt::print("dot: {} (render with: dot -Tsvg {} -o graph.svg)\n", dotPath.string(), dotPath.string());
  return kExitOk;
}

}  // namespace

void registerGraphCommand(CLI::App& app, const Technique& help) {
  auto args = std::make_shared<GraphArgs>();
  auto* cmd = app.add_subcommand("graph", "print the compiled render graph and write it as Graphviz DOT");
  cmd->add_option("capture", args->capture, "capture folder")->required();
  args->settings.add(*cmd, help);
  cmd->add_option("--dot", args->dot, "DOT output file (default out/<capture name>/graph.dot; - for standard output)");
  handlers()["graph"] = [args] { return graphCommand(*args); };
}

}  // namespace aor::cli
