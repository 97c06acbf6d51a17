// ao_bench: GPU time of each pass and of the whole AO pipeline, per preset and resolution, from
// Vulkan timestamp queries, reported to Google Benchmark as manual time (so its JSON is what
// Debian's compare.py and `aoreplay compare` read). Besides the presets, each size has the high
// preset with bent=0 (pipeline only) and with half_res=1 (every pass).
//
// Each configuration replays frames 0:2 of the capture once (pipelines are compiled in the
// replay's set-up, warm-ups run first) with `--reps` timed executions per frame; the second frame has valid
// history, so the temporal pass runs. Its timed executions are the samples: benchmark repetition i
// reports execution i. The GPU work is real and measured per execution; only the bookkeeping is
// batched, so setting up Vulkan pipelines is not paid once per sample.
//
// Own flags (before Google Benchmark's): --sizes=320x180,640x360,1920x1080  --presets=low,medium,high,ultra
// --reps=N (default 10)  --warmup=N (default 2)  --warmup-ms=MS (default 300)  --device=SEL  --capture=DIR  --cache=DIR
// --scaling-size=WxH: where time against slices x steps is measured (default: the second size).
// Sizes are read by aor::parseSize (options/size.h), as `aoreplay capture --size` is, numbers by
// aor::parseInt/parseNumber (options/number.h); a bad value exits 2 before any device is opened.
// --extra-slices=N (0..23) adds N GTAO slices to every configuration without renaming it: a real
// slowdown for checking that `aoreplay compare` detects one (ultra's 9 + 23 is the 32-slice limit).
//
// Warm-up is by time as well as by count: a GPU needs some hundred milliseconds of steady work to
// leave its idle clocks, and a configuration measured in a 5 ms burst is measured at whatever clock
// the previous one left (seen on the H100: one configuration 40% slower in one of two runs). A
// probe execution times one frame; warm-ups are repeated until they add up to --warmup-ms.
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <memory>
#include <sstream>

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include "bench_capture.h"
#include "bench_scaling.h"
#include "capture/input_error.h"
#include "options/number.h"
#include "options/size.h"
#include "pipeline/replayer.h"
#include "report/compare_stats.h"
#include "report/pipeline_time.h"
#include "report/run_outputs.h"
#include "report/stats.h"
#include "vk/context.h"

namespace aor::bench {
namespace {

struct Options {
  std::vector<std::pair<int, int>> sizes{{320, 180}, {640, 360}, {1920, 1080}};
  std::vector<std::string> presets{"low", "medium", "high", "ultra"};
  int reps = 10;
  int warmup = 2;
  double warmupMs = 300;
  int extraSlices = 0;
  std::optional<std::pair<int, int>> scalingSize;
  std::string device;
  std::string capture = AOR_SOURCE_DIR "/captures/boxes-orbit";
  std::string cache = "bench-captures";
};

struct Config {
  int width = 0, height = 0;
  AoSettings settings;
  std::string label() const {
    return fmt::format("s{}x{}{}{}/{}x{}", settings.slices, settings.steps, settings.bent ? "" : "/bent:0",
                       settings.halfRes ? "/half_res:1" : "", width, height);
  }
  auto key() const { return std::tuple(width, height, settings.slices, settings.steps, settings.bent, settings.halfRes); }
};

struct Measured {
  std::map<std::string, std::vector<double>> passMs;  // per pass, one sample per timed execution
  std::vector<double> pipelineMs;                      // repetitionSumsMs: the compute passes, per execution
};

class Harness {
 public:
  explicit Harness(Options o) : options_(std::move(o)), context_({options_.device, false}) {}
  const Options& options() const { return options_; }
  const DeviceInfo& device() const { return context_.vk.info; }

  int warmupRuns(double executionMs) const {
    int byTime = int(std::ceil(options_.warmupMs / std::max(executionMs, 0.001)));
    return std::clamp(byTime, options_.warmup, 5000);
  }

  const Measured* alreadyMeasured(const Config& config) const {
    auto found = measured_.find(config.key());
    return found == measured_.end() ? nullptr : &found->second;
  }

  const Measured& measure(const Config& config) {
    auto found = measured_.find(config.key());
    if (found != measured_.end()) return found->second;
    Capture capture = resampledCapture(options_.capture, config.width, config.height, 2, options_.cache);
    ReplayOptions replay;
    replay.settings = settingsForCapture(capture, config.settings, false);
    replay.settings.slices += options_.extraSlices;
    replay.frameBegin = 0;
    replay.frameEnd = 1;
    auto probe = replayCapture(context_.vk, capture, replay, nullptr);
    replay.frameEnd = 2;
    replay.repeat = options_.reps;
    replay.warmup = warmupRuns(probe.frames.front().gpuWallMs);
    auto result = replayCapture(context_.vk, capture, replay, nullptr);
    Measured m;
    const auto& frame = result.frames.back();
    for (const auto& pass : frame.passes) m.passMs[pass.name] = pass.durationsMs;
    // The run total's definition (report/pipeline_time.h): Google Benchmark's median of these
    // samples is the frame's totalMedianMs.
    m.pipelineMs = repetitionSumsMs({timedFrame(frame)}, PassGroup::Compute);
    return measured_.emplace(config.key(), std::move(m)).first->second;
  }

 private:
  Options options_;
  ContextScope context_;
  std::map<decltype(Config{}.key()), Measured> measured_;
};

Harness* harness = nullptr;

// One benchmark = one series of samples; repetition i reports sample i as manual time.
void registerSeries(const std::string& name, Config config, std::string pass) {
  auto next = std::make_shared<size_t>(0);
  benchmark::RegisterBenchmark(name.c_str(), [config, pass, next](benchmark::State& state) {
    const auto& m = harness->measure(config);
    const auto& samples = pass == "pipeline" ? m.pipelineMs : m.passMs.at(pass);
    for (auto _ : state) state.SetIterationTime(samples.at(*next % samples.size()) / 1000.0);
    ++*next;
    state.counters["pixels"] = double(config.width) * double(config.height);
    state.counters["slice_steps"] = double(config.settings.slices * config.settings.steps);
  })
      ->UseManualTime()
      ->Iterations(1)
      ->Repetitions(harness->options().reps)
      ->Unit(benchmark::kMillisecond);
}

void registerConfig(const Config& config, bool perPass) {
  registerSeries("pipeline/" + config.label(), config, "pipeline");
  if (!perPass) return;
  for (const char* pass : {"linearize_depth", "gtao", "spatial_columns", "spatial", "temporal", "upload", "readback"})
    registerSeries(std::string(pass) + "/" + config.label(), config, pass);
}

Config makeConfig(int w, int h, const std::string& preset, int bent, int halfRes = 0) {
  Config c{w, h, {}};
  applyPreset(c.settings, preset);
  c.settings.bent = bent;
  c.settings.halfRes = halfRes;
  return c;
}

// Slices x steps beyond the presets, at one size, for the scaling fit.
const std::vector<std::pair<int, int>> kScalingSliceSteps{{1, 2}, {2, 2}, {2, 4}, {3, 3}, {4, 4}, {9, 3}, {6, 6}};

std::pair<int, int> scalingSize();

// The scaling fit's configurations: the high preset with each of kScalingSliceSteps, at
// scalingSize(). Registration and the fit both take them from here.
std::vector<Config> scalingConfigs() {
  auto [w, h] = scalingSize();
  std::vector<Config> configs;
  for (auto [slices, steps] : kScalingSliceSteps) {
    Config c = makeConfig(w, h, "high", 1);
    c.settings.slices = slices;
    c.settings.steps = steps;
    configs.push_back(c);
  }
  return configs;
}

void registerAll() {
  const auto& o = harness->options();
  for (auto [w, h] : o.sizes) {
    for (const auto& preset : o.presets) registerConfig(makeConfig(w, h, preset, 1), true);
    registerConfig(makeConfig(w, h, "high", 0), false);  // bent=0 vs bent=1
    registerConfig(makeConfig(w, h, "high", 1, 1), true);  // half_res=1: GTAO and the blur at half size
  }
  for (const auto& c : scalingConfigs()) registerSeries("gtao/" + c.label(), c, "gtao");
}

std::pair<int, int> scalingSize() {
  const auto& o = harness->options();
  return o.scalingSize ? *o.scalingSize : o.sizes.size() > 1 ? o.sizes[1] : o.sizes[0];
}

ScalingInput scalingInput() {
  const auto& o = harness->options();
  ScalingInput in;
  // Only what the benchmark filter let run.
  for (auto [w, h] : o.sizes)
    if (const auto* m = harness->alreadyMeasured(makeConfig(w, h, "high", 1)))
      in.byPixels.push_back({double(w) * h, summarize(m->pipelineMs).median});
  for (const auto& c : scalingConfigs())
    if (const auto* m = harness->alreadyMeasured(c))
      in.bySliceSteps.push_back({double(c.settings.slices * c.settings.steps), medianOf(m->passMs.at("gtao"))});
  auto [w, h] = scalingSize();
  in.sliceStepsSize = fmt::format("{}x{}", w, h);
  return in;
}

std::vector<std::string> splitList(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');) out.push_back(item);
  return out;
}

// Takes the flags this program owns out of argv, leaving Google Benchmark's.
Options parseOwnFlags(int& argc, char** argv) {
  Options o;
  int kept = 1;
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    auto value = [&](const char* flag) -> std::optional<std::string> {
      std::string prefix = std::string(flag) + "=";
      if (arg.rfind(prefix, 0) == 0) return arg.substr(prefix.size());
      return std::nullopt;
    };
    if (auto v = value("--sizes")) {
      o.sizes.clear();
      for (const auto& s : splitList(*v)) o.sizes.push_back(parseSize(s, "--sizes"));
      if (o.sizes.empty()) throw InputError("", std::nullopt, "--sizes", "names no size (expected WxH,WxH,...)");
    } else if (auto ss = value("--scaling-size")) o.scalingSize = parseSize(*ss, "--scaling-size");
    else if (auto p = value("--presets")) o.presets = splitList(*p);
    else if (auto r = value("--reps")) o.reps = parseInt(*r, "--reps", 5, 100000);  // compare needs 5 a side
    else if (auto wu = value("--warmup")) o.warmup = parseInt(*wu, "--warmup", 0, 100000);
    else if (auto wm = value("--warmup-ms")) o.warmupMs = parseNumber(*wm, "--warmup-ms", 0.0, 600000.0);
    else if (auto es = value("--extra-slices")) o.extraSlices = parseInt(*es, "--extra-slices", 0, 23);
    else if (auto d = value("--device")) o.device = *d;
    else if (auto c = value("--capture")) o.capture = *c;
    else if (auto c2 = value("--cache")) o.cache = *c2;
    else argv[kept++] = argv[i];
  }
  argc = kept;
  return o;
}

}  // namespace
}  // namespace aor::bench

int main(int argc, char** argv) {
  using namespace aor::bench;
  try {
    Harness h(parseOwnFlags(argc, argv));
    harness = &h;
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 2;
    benchmark::AddCustomContext("vulkan_device", h.device().name);
    benchmark::AddCustomContext("vulkan_driver", h.device().driver);
    registerAll();
    benchmark::RunSpecifiedBenchmarks();
    printScaling(stderr, scalingInput());
    benchmark::Shutdown();
  } catch (const aor::InputError& e) {  // bad usage, like an unrecognised flag: exit 2
    fmt::print(stderr, "ao_bench: error: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "ao_bench: {}\n", e.what());
    return 1;
  }
  return 0;
}
