// `aoreplay run`: replay a capture, time each pass, write images, report.json and trace.json.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>

#include <fmt/format.h>

#include "cli/commands.h"
#include "cost/launcher.h"
#include "cli/cost_option.h"
#include "run/counted.h"
#include "cli/handlers.h"
#include "cli/number_options.h"
#include "options/progress.h"
#include "cli/settings_options.h"
#include "metrics/depth.h"
#include "run/run.h"
#include "report/expectations.h"
#include "report/html/run_page.h"
#include "report/junit.h"
#include "core/output_directory.h"
#include "report/run_outputs.h"
#include "report/run_summary.h"
#include "report/temporal_plot.h"
#include "vk/context.h"
#include "vk/vk_check.h"

namespace aor::cli {
namespace {

namespace fs = std::filesystem;

struct RunArgs {
  std::string capture;
  SettingsOptions settings;
  int repeat = 1;
  int warmup = 1;  // lavapipe compiles a shader on its first dispatch: keep that out of the timed runs
  bool overlap = false, isolate = false;
  double preloadBudgetMiB = double(kDefaultPreloadBudgetBytes >> 20);
  std::string out;
  std::string device;
  bool validate = false;
  bool noImages = false;
  bool keepHistoryOnCut = false;
  CameraJumpLimits cameraJump;
  std::string expect;  // thresholds file (report/expectations.h)
  std::string junit;   // JUnit XML of the --expect checks
  CostMeasure cost = CostMeasure::Time;
};

// The frames report.html shows, and the previous frame of each (for flicker), kept as they pass.
class ShownFrames {
 public:
  explicit ShownFrames(std::vector<int> shown) : shown_(std::move(shown)) {}
  void keep(const Capture& capture, const FrameOutput& frame) {
    bool isShown = std::find(shown_.begin(), shown_.end(), frame.index) != shown_.end();
    bool isPrevious = std::find(shown_.begin(), shown_.end(), frame.index + 1) != shown_.end();
    if (isPrevious) previous_[frame.index] = frame.visibility;
    if (!isShown) return;
    html::FrameImages images{frame.index, frame.width, frame.height, frame.visibility, loadReference(capture, frame.index), {}, {}};
    const auto& desc = capture.frames[size_t(frame.index)];
    float far = isReversedDepth(desc.projection) ? 0.0f : 1.0f;
    images.sky.resize(frame.visibility.size());
    for (size_t i = 0; i < images.sky.size() && i < frame.gbuffer->depth.size(); ++i)
      images.sky[i] = !std::isfinite(frame.gbuffer->depth[i]) || frame.gbuffer->depth[i] == far;
    frames_.push_back(std::move(images));
  }
  std::vector<html::FrameImages> take() {
    for (auto& f : frames_)
      if (auto it = previous_.find(f.index - 1); it != previous_.end()) f.previousAo = it->second;
    return std::move(frames_);
  }

 private:
  std::vector<int> shown_;
  std::map<int, std::vector<float>> previous_;
  std::vector<html::FrameImages> frames_;
};

ReplayOptions replayOptionsOf(const RunArgs& args, const Capture& capture) {
  ReplayOptions options(args.settings.resolve(capture));
  std::tie(options.frameBegin, options.frameEnd) = args.settings.frameRange(capture);
  options.debugViews = {args.settings.debugViews.begin(), args.settings.debugViews.end()};
  options.repeat = args.repeat;
  options.warmup = args.warmup;
  if (args.overlap && args.isolate) throw InputError("", std::nullopt, "--overlap", "--overlap and --isolate exclude each other");
  options.timingMode = args.overlap ? TimingMode::Overlapped : args.isolate ? TimingMode::Isolated : TimingMode::Auto;
  options.preloadBudgetBytes = uint64_t(args.preloadBudgetMiB * double(1 << 20));
  options.keepHistoryOnCut = args.keepHistoryOnCut;
  options.cameraJump = args.cameraJump;
  options.progress = progressCallback("replay", "frames");
  if (args.cost != CostMeasure::Time) prepareCountedReplay(args.cost, {args.repeat, args.overlap, args.validate}, options);
  return options;
}

struct Replayed {
  RunResults run;
  std::vector<html::FrameImages> shown;
  size_t validationMessages = 0;
};

Replayed replay(const RunArgs& args, const Capture& capture, const ReplayOptions& options, const OutputDirectory& out) {
  ShownFrames shown(html::framesToShow(options.frameBegin, options.frameEnd));
  ContextScope context({args.device, args.validate, optionalExtensionsOf({options.settings})});
  prepareCountedContext(context.vk, args.cost);
  RunResults run = runCapture(context.vk, capture, RunRequest(options), [&](const FrameOutput& frame) {
    if (!args.noImages) writeFrameImages(out.staging(), frame);
    for (const auto& view : frame.debugImages) writeDebugImage(out.staging(), frame.index, view);
    shown.keep(capture, frame);
  });
  destroyContext(context.vk);  // waits for the device; the last validation messages arrive here
  return {std::move(run), shown.take(), context.vk.validationMessageCount()};
}

void printRun(const Capture& capture, const ReplayOptions& options, const ReplayResult& result, const nlohmann::json& report,
              const std::vector<std::string>& summary) {
  fmt::print("device: {} ({})\n", result.device.name, result.device.driver);
  fmt::print("capture: {} ({}x{}, frames {}:{}), settings: {}\n", capture.name, capture.width, capture.height,
             options.frameBegin, options.frameEnd, options.settings.toJson().dump());
  fmt::print("{}", options.cost == CostMeasure::Time ? passTable(result) : countedPassTable(result, options.cost));
  for (const auto& c : result.culled) fmt::print("culled: {} ({})\n", c.name, c.reason);
  for (const auto& line : summary) fmt::print("{}\n", line);
  HostOverhead overhead = hostOverhead(result);
  fmt::print("set-up: {:.1f} ms (pipelines{})\n", result.setupMs,
             result.timingMode == TimingMode::Overlapped ? "; the first frame's decode overlaps it" : "");
  fmt::print("wall: {:.1f} ms for {} frame(s), {:.1f} frames/s; host overhead {:.1f} ms ({:.1f} % of wall); timing {}{}\n",
             result.wallMs, result.frames.size(), report["replay_fps"].get<double>(), overhead.ms,
             100.0 * overhead.fractionOfWall, timingModeName(result.timingMode),
             result.timingMode == TimingMode::Isolated ? fmt::format(" ({} frame(s) a chunk)", result.chunkFrames) : "");
}

// After the commit: --junit's file and the expectations' verdict.
int reportExpectations(const RunArgs& args, const std::vector<Threshold>& expectations,
                       const std::vector<ExpectationFailure>& failures, const std::vector<fs::path>& inputs) {
  if (!args.junit.empty()) {
    auto cases = expectationCases(expectations, failures);
    writeFileAtomically(args.junit, junitXml("aoreplay run --expect " + args.expect, cases), inputs);
    fmt::print("junit: {} ({} test case(s), {} failed)\n", args.junit, cases.size(),
               std::count_if(cases.begin(), cases.end(), [](const JunitCase& c) { return c.failure.has_value(); }));
  }
  if (failures.empty()) {
    if (!expectations.empty()) fmt::print("expectations: all {} met ({})\n", expectations.size(), args.expect);
    return kExitOk;
  }
  fmt::print(stderr, "aoreplay: {} expectation(s) from {} not met:\n", failures.size(), args.expect);
  for (const auto& f : failures) fmt::print(stderr, "  {}\n", f.describe());
  return kExitFailed;
}

int runCommand(const RunArgs& args) {
  if (args.cost != CostMeasure::Time && !CallgrindCounter::underCallgrind()) return runUnderCallgrind(args.cost);
  Capture capture = loadCapture(args.capture);
  std::vector<Threshold> expectations;
  if (!args.expect.empty()) expectations = loadExpectations(args.expect);
  ReplayOptions options = replayOptionsOf(args, capture);
  std::vector<fs::path> inputs = {capture.folder};
  if (!args.expect.empty()) inputs.emplace_back(args.expect);
  OutputDirectory out(args.out.empty() ? fs::path("out") / capture.name : fs::path(args.out), ResultKind::Run, inputs);

  Replayed replayed = replay(args, capture, options, out);
  const ReplayResult& result = replayed.run.replay;
  auto report = buildReport(capture, options, replayed.run);
  report["validation"] = {{"enabled", args.validate}, {"messages", replayed.validationMessages}};
  writeJson(out.staging() / "report.json", report);
  writeJson(out.staging() / "trace.json", buildTrace(result));
  writeTemporalPlots(out.staging(), report, result.noHistoryReason);
  std::vector<std::string> summary = {errorLine(report), temporalLine(report)};
  writeText(out.staging() / "report.html",
            html::runPageHtml({report, std::move(replayed.shown), result.graph, summary, result.noHistoryReason}));
  printRun(capture, options, result, report, summary);
  if (args.validate && replayed.validationMessages > 0) {
    fmt::print(stderr, "aoreplay: {} validation message(s); the run failed and wrote no results\n", replayed.validationMessages);
    return kExitFailed;
  }
  // Before the commit: a threshold naming a metric the report lacks is bad input and leaves nothing.
  auto failures = checkExpectations(expectations, report, args.expect);
  std::string written = outputListing(out.staging());
  out.commit();
  if (args.validate) fmt::print("validation: 0 messages (synchronization validation on)\n");
  fmt::print("outputs: {}/ ({}{})\n", out.finalPath().string(), written, args.noImages ? "; frame images skipped by --no-images" : "");
  return reportExpectations(args, expectations, failures, inputs);
}

}  // namespace

void registerRunCommand(CLI::App& app, const Technique& help) {
  auto args = std::make_shared<RunArgs>();
  auto* cmd = app.add_subcommand("run", "replay a capture through a technique's render graph, time each pass");
  cmd->add_option("capture", args->capture, "capture folder (holding capture.json)")->required();
  args->settings.add(*cmd, help);
  cmd->add_option("--repeat", args->repeat, "timed executions of each frame")->check(wholeIn(1, 100000))->capture_default_str();
  cmd->add_option("--warmup", args->warmup, "untimed executions of each frame before timing")
      ->check(wholeIn(0, 100000))
      ->capture_default_str();
  cmd->add_flag("--overlap", args->overlap,
                "decode the next frame and sink the last one on workers while a frame is timed (the most frames per "
                "second; the default on a GPU)");
  cmd->add_flag("--isolate", args->isolate,
                "no thread of the tool runs while a frame is timed: frames are preloaded in chunks and sunk after "
                "(the default on a CPU device: lavapipe, llvmpipe, SwiftShader)");
  cmd->add_option("--preload-budget", args->preloadBudgetMiB, "MiB a chunk of preloaded frames may hold (isolated timing)")
      ->check(numberIn(1.0, 1048576.0))
      ->capture_default_str();
  cmd->add_option("--out", args->out, "output folder (default out/<capture name>/)");
  cmd->add_option("--device", args->device, kDeviceHelp);
  cmd->add_flag("--validate", args->validate, "Khronos validation + synchronization validation; any message fails");
  cmd->add_flag("--no-images", args->noImages, "skip writing per-frame EXR/PNG");
  cmd->add_option("--expect", args->expect,
                  "JSON thresholds {\"max\": {METRIC: limit}, \"min\": {...}}; any violation: exit 1 after writing outputs");
  cmd->add_option("--junit", args->junit,
                  "with --expect: also write the checks as JUnit XML to this file (one test case per threshold)")
      ->needs(cmd->get_option("--expect"));
  cmd->add_option("--jump-angle", args->cameraJump.maxRotationDegrees,
                  "reset history when the camera turns more than this many degrees between frames (0 = off)")
      ->check(numberIn(0.0, 180.0))
      ->capture_default_str();
  cmd->add_option("--jump-distance", args->cameraJump.maxMoveFraction,
                  "reset history when the camera moves more than this fraction of the median view distance (0 = off)")
      ->check(numberIn(0.0, 1e12))
      ->capture_default_str();
  addCostOption(*cmd, args->cost,
                "time: GPU timestamps; instructions or cycles: each pass's work counted under valgrind's callgrind "
                "on lavapipe (instructions exact, 20-100x slower; cycles from its cache simulation)");
  cmd->add_flag("--test-keep-history-on-cut", args->keepHistoryOnCut,
                "TEST ONLY: do not reset history on a cut (proves the cut check can fail)")
      ->group("");
  handlers()["run"] = [args] { return runCommand(*args); };
}

void registerDevicesCommand(CLI::App& app) {
  app.add_subcommand("devices", "list Vulkan devices (index, name, driver; [ray queries]: rtao's ray-query path runs there)");
  handlers()["devices"] = [] {
    auto devices = listDevices();
    if (devices.empty()) throw NoDeviceError("no Vulkan device found");
    for (const auto& d : devices)
      fmt::print("{}: {} ({}, Vulkan {}){}{}\n", d.index, d.name, d.driver, d.apiVersion, d.isLavapipe ? " [default]" : "",
                 d.hasExtension(kRayQueryExtension) && d.hasExtension(kAccelerationStructureExtension) ? " [ray queries]" : "");
    return kExitOk;
  };
}

}  // namespace aor::cli
