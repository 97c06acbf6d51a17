// `aoreplay sweep`: replays a capture under several configurations in one Vulkan context and
// puts each one's GPU time next to its error against the reference (table, sweep.json/.csv/.svg).
#include <chrono>
#include <filesystem>
#include <map>
#include <memory>

#include <fmt/format.h>

#include "capture/library.h"
#include "cli/commands.h"
#include "cost/launcher.h"
#include "cli/cost_option.h"
#include "run/counted.h"
#include "cli/handlers.h"
#include "cli/number_options.h"
#include "options/progress.h"
#include "cli/settings_options.h"
#include "run/run.h"
#include "techniques/registry.h"
#include "techniques/settings_file.h"
#include "report/html/sweep_page.h"
#include "core/output_directory.h"
#include "report/run_outputs.h"
#include "report/sweep.h"
#include "vk/context.h"

namespace aor::cli {
namespace {

namespace fs = std::filesystem;

struct SweepArgs {
  std::string capture;
  std::string presets;  // comma-separated; empty: every preset of each technique
  std::vector<std::string> grid;
  long long maxConfigurations = kDefaultMaxConfigurations;
  std::vector<std::string> assignments;
  std::string settingsFile;  // --settings FILE: technique, preset, keys and radius scale to start from
  std::string frames;
  int repeat = 3;
  int warmup = 1;
  std::string out;
  std::string device;
  SweepRank rank = SweepRank::Rmse;
  CostMeasure cost = CostMeasure::Time;
  bool repeatGiven = false;  // --repeat on the command line (counted cost takes one run a frame)
};

SweepRow measure(VulkanContext& vk, const Capture& capture, const ReplayOptions& options, const SweepConfig& config,
                 const References& references) {
  RunRequest request(options);
  request.replay.settings = config.settings;
  request.references = &references;
  request.temporal = false;
  return sweepRow(config, runCapture(vk, capture, request));
}

std::vector<std::string> splitPresets(const std::string& text) {
  std::vector<std::string> presets;
  if (text.empty()) return presets;
  for (size_t start = 0; start <= text.size();) {
    size_t comma = std::min(text.find(',', start), text.size());
    presets.push_back(text.substr(start, comma - start));
    start = comma + 1;
  }
  return presets;
}

// One capture's sweep into `outFolder` (empty: out/<capture name>-sweep/).
int sweepCapture(const SweepArgs& args, const std::string& capturePath, const std::string& outFolder) {
  Capture capture = loadCapture(capturePath);
  SettingsOptions range;
  range.frames = args.frames;
  auto [begin, end] = range.frameRange(capture);
  SweepRequest request{splitPresets(args.presets), args.grid, args.assignments};
  request.maxConfigurations = size_t(args.maxConfigurations);
  SettingsRecipe base{request.defaultTechnique, "", {}, 1.0};
  if (!args.settingsFile.empty()) {
    base = readSettingsFile(args.settingsFile);
    request.defaultTechnique = base.technique;
    if (request.presets.empty() && !base.preset.empty()) request.presets = {base.preset};
    request.assignments.insert(request.assignments.begin(), base.assignments.begin(), base.assignments.end());
  }
  auto plan = expandSweep(request, [&](const Technique& t, std::string_view preset, const std::vector<std::string>& assignments) {
    double scale = t.name == base.technique ? base.radiusScale : 1.0;
    return SettingsRecipe{t.name, std::string(preset), assignments, scale}.resolve(capture);
  });  // bad presets, keys and grids fail before any work
  for (const auto& note : plan.notes) fmt::print(stderr, "{}\n", note);
  if (plan.configs.empty())
    throw InputError("", std::nullopt, "--presets", fmt::format("'{}' leaves nothing to sweep", args.presets));
  const auto& configs = plan.configs;
  ReplayOptions options(configs.front().settings);
  options.frameBegin = begin;
  options.frameEnd = end;
  options.repeat = args.repeat;
  options.warmup = args.warmup;
  if (args.cost != CostMeasure::Time) {
    options.repeat = args.repeatGiven ? args.repeat : 1;
    prepareCountedReplay(args.cost, {options.repeat, false, false}, options);
  }
  OutputDirectory out(outFolder.empty() ? fs::path("out") / (capture.name + "-sweep") : fs::path(outFolder),
                      ResultKind::Sweep, {capture.folder});

  SweepInfo info{capture.name, "", "", costMeasureName(args.cost), options.frameBegin, options.frameEnd, options.repeat,
                 options.warmup, args.rank};
  std::vector<SweepRow> rows;
  {
    std::vector<Settings> runs;
    for (const auto& config : configs) runs.push_back(config.settings);
    ContextScope context({args.device, false, optionalExtensionsOf(std::move(runs))});
    info.device = context.vk.info.name;
    prepareCountedContext(context.vk, args.cost);
    auto reference = completeReferences(context.vk, capture, begin, end, args.assignments);
    info.referenceKind = reference.kind;
    // A line per configuration, with the time left estimated from the ones done (cli/progress.h).
    auto start = std::chrono::steady_clock::now();
    for (size_t i = 0; i < configs.size(); ++i) {
      double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      fmt::print(stderr, "[{}/{}] {} ({})\n", i + 1, configs.size(), configs[i].name,
                 Progress::status("configurations", int(i), int(configs.size()), elapsed));
      rows.push_back(measure(context.vk, capture, options, configs[i], reference));
    }
  }
  markPareto(rows, args.rank);
  writeJson(out.staging() / "sweep.json", sweepJson(info, rows));
  writeText(out.staging() / "sweep.csv", sweepCsv(rows));
  writeText(out.staging() / "sweep.svg", sweepSvg(info, rows));
  writeText(out.staging() / "sweep.html", html::sweepPageHtml(info, rows));
  out.commit();

  fmt::print("capture: {} (frames {}:{}), device: {}, error against the {} reference, {}\n", capture.name,
             options.frameBegin, options.frameEnd, info.device, info.referenceKind,
             args.cost == CostMeasure::Time ? fmt::format("{} timed run(s) per frame", args.repeat)
                                            : fmt::format("{} counted under callgrind", costMeasureName(args.cost)));
  fmt::print("{}", sweepTable(rows));
  fmt::print("outputs: {}/ (sweep.json, sweep.csv, sweep.svg, sweep.html)\n", out.finalPath().string());
  return kExitOk;
}

// A library (a folder of captures, capture/library.h) is swept capture by capture, each into
// OUT/<capture name>/ (OUT default out/<library name>-sweep/).
int sweepCommand(const SweepArgs& args) {
  if (args.cost != CostMeasure::Time && !CallgrindCounter::underCallgrind()) return runUnderCallgrind(args.cost);
  if (!isCaptureLibrary(args.capture)) return sweepCapture(args, args.capture, args.out);
  const auto folders = captureFoldersOf({args.capture});
  const fs::path base = args.out.empty() ? fs::path("out") / (fs::path(args.capture).filename().string() + "-sweep") : fs::path(args.out);
  for (size_t i = 0; i < folders.size(); ++i) {
    const std::string name = fs::path(folders[i]).filename().string();
    fmt::print(stderr, "library: capture {} of {}: {}\n", i + 1, folders.size(), name);
    sweepCapture(args, folders[i], (base / name).string());
  }
  return kExitOk;
}

}  // namespace

void registerSweepCommand(CLI::App& app, const Technique& help) {
  auto args = std::make_shared<SweepArgs>();
  auto* cmd = app.add_subcommand("sweep", "replay a capture under several settings: error against GPU time, Pareto front");
  cmd->add_option("capture", args->capture,
                  "capture folder (holding capture.json), or a library: a folder of capture folders, each swept into "
                  "OUT/<capture name>/")
      ->required();
  cmd->add_option("--presets", args->presets,
                  fmt::format("comma-separated presets to run (default: every preset of each technique; {}: {})", help.name,
                              help.presetList()));
  cmd->add_option("--grid", args->grid,
                  "KEY=v1,v2,..., repeatable: every preset is run with every combination; KEY is `technique` or a key "
                  "of a technique in the sweep (applied to those that have it)");
  cmd->add_option("--max-configurations", args->maxConfigurations,
                  "refuse a sweep of more configurations than this (each is a run of the capture)")
      ->check(wholeIn(1, 100'000'000))
      ->capture_default_str();
  cmd->add_option("--set", args->assignments,
                  "KEY=VALUE applied to every configuration whose technique has the key, before the grid");
  cmd->add_option("--settings", args->settingsFile,
                  "settings file (as `aoreplay tune` writes): its technique is the default, its preset the default "
                  "preset, its keys go before --set, its radius scale applies to its technique");
  cmd->add_option("--frames", args->frames, "half-open frame range A:B (default: all)");
  auto* repeat = cmd->add_option("--repeat", args->repeat, "timed executions of each frame (counted cost: 1)")
                     ->check(wholeIn(1, 100000))
                     ->capture_default_str();
  cmd->add_option("--warmup", args->warmup, "untimed executions of each frame first")->check(wholeIn(0, 100000))->capture_default_str();
  cmd->add_option("--out", args->out, "output folder (default out/<capture name>-sweep/, a library's out/<library name>-sweep/)");
  cmd->add_option("--device", args->device, kDeviceHelp);
  cmd->add_option("--rank-by", args->rank,
                  "the error the plot and the Pareto front use: rmse (every surface pixel) or halo_band (the "
                  "background behind nearer silhouettes, metrics.error.halo_band)")
      ->transform(CLI::CheckedTransformer(std::map<std::string, SweepRank>{{"rmse", SweepRank::Rmse},
                                                                           {"halo_band", SweepRank::HaloBand}}))
      ->default_str("rmse");
  cmd->footer(fmt::format("Keys of technique {} (aoreplay techniques lists every technique's):\n{}", help.name,
                          keyTable(help)));
  addCostOption(*cmd, args->cost,
                "time, or instructions or cycles: each configuration's passes counted under callgrind on lavapipe "
                "(run --cost; one run a frame)");
  handlers()["sweep"] = [args, repeat] {
    args->repeatGiven = repeat->count() > 0;
    return sweepCommand(*args);
  };
}

}  // namespace aor::cli
