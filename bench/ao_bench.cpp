// ao_bench: GPU time of each pass and of the whole pipeline of a technique, per preset and
// resolution, from Vulkan timestamp queries, reported to Google Benchmark as manual time (so its
// JSON is what Debian's compare.py and `aoreplay compare` read). Every technique is benchmarked the
// same way, from its declarations: its presets, its passes (whatever its graph runs), and extra
// configurations given as --set assignments.
//
// Each configuration replays frames 0:2 of the capture once (pipelines are compiled in the
// replay's set-up, warm-ups run first) with `--reps` timed executions per frame; the second frame has valid
// history, so a technique's history passes run. Its timed executions are the samples: benchmark
// repetition i reports execution i. The GPU work is real and measured per execution; only the
// bookkeeping is batched, so setting up Vulkan pipelines is not paid once per sample.
// Names: PASS/TECHNIQUE/PRESET[/KEY:VALUE...]/WxH, and `pipeline` for the sum of the compute passes.
//
// Own flags (before Google Benchmark's): --technique=NAME[,NAME...] (default gtao; a value with
// a '/' or ending in .json is a user technique's technique.json, user_techniques/FORMAT.md)
// --sizes=320x180,640x360,1920x1080  --presets=NAME,... (default: every preset of each technique)
// --extra=KEY=VALUE[;KEY=VALUE...] (repeatable: one more configuration per size, the default preset
// with those assignments; e.g. --extra=bent=0 --extra=half_res=1 for gtao)
// --reps=N (default 10)  --warmup=N (default 2)  --warmup-ms=MS (default 300)  --device=SEL  --capture=DIR  --cache=DIR
// --scaling-size=WxH: where time against slices x steps is measured (default: the second size), for
// techniques with `slices` and `steps` keys.
// Sizes are read by aor::parseSize (options/size.h), as `aoreplay capture --size` is, numbers by
// aor::parseInt/parseNumber (options/number.h); a bad value exits 2 before any device is opened.
// --extra-slices=N (0..23) adds N to the `slices` key of every configuration without renaming it: a
// real slowdown for checking that `aoreplay compare` detects one.
//
// --floor: after the benchmarks, replays each configuration once more through the counting build of
// its shaders (vk/op_counter.h; frames 0:2, counts of the second), measures the device's copy
// bandwidth and texelFetch rate (device_rates.h: --rate-mib=MIB, default 256, --rate-size=WxH,
// default 3840x2160), and prints per pass: counts, measured ms, floor ms, ratio (floor.h);
// --floor-json=PATH writes the same as JSON. --no-rates: counts only (floor times 0), e.g. on lavapipe
// with --benchmark_filter=none to skip the timing, as counts do not depend on the device.
//
// --cost=instructions|cycles (docs/guide.md, "Counted cost"): counts instead of times. ao_bench re-executes
// itself under callgrind as `aoreplay run --cost` does; each configuration replays frames 0:2 once
// (a warm-up first), and each pass of the second frame and `pipeline` (the compute passes' sum) is
// one repetition whose real_time holds the count (not ms), with a counter named after the measure;
// the context's aoreplay_cost block (as report.json's "cost") lets `aoreplay compare` judge counts
// exactly; the scaling fit (of milliseconds) is left out. --reps, --warmup, --warmup-ms and --floor are refused with counts (exit 2): counts are
// taken once, need no clock warm-up, and the floor is a timed measurement. --cost=time is the default.
//
// Warm-up is by time as well as by count: a GPU needs some hundred milliseconds of steady work to
// leave its idle clocks, and a configuration measured in a 5 ms burst is measured at whatever clock
// the previous one left (seen on the H100: one configuration 40% slower in one of two runs). A
// probe execution times one frame; warm-ups are repeated until they add up to --warmup-ms.
#include <algorithm>
#include <fstream>
#include <cmath>
#include <map>
#include <optional>
#include <memory>
#include <sstream>

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include "bench_capture.h"
#include "bench_scaling.h"
#include "device_rates.h"
#include "floor.h"
#include "core/input_error.h"
#include "core/pass_names.h"
#include "options/number.h"
#include "options/size.h"
#include "replay_loop/replayer.h"
#include "techniques/built_frame.h"
#include "techniques/registry.h"
#include "core/compare_stats.h"
#include "run/gpu_total.h"
#include "report/run_outputs.h"
#include "core/stats.h"
#include "cost/launcher.h"
#include "run/counted.h"
#include "vk/context.h"
#include "vk/op_counter.h"

namespace aor::bench {
namespace {

struct Options {
  std::vector<std::pair<int, int>> sizes{{320, 180}, {640, 360}, {1920, 1080}};
  std::vector<std::string> techniques{"gtao"};
  std::vector<std::string> presets;  // empty: every preset of each technique
  std::vector<std::vector<std::string>> extras;
  int reps = 10;
  int warmup = 2;
  double warmupMs = 300;
  int extraSlices = 0;
  std::optional<std::pair<int, int>> scalingSize;
  std::string device;
  std::string capture = AOR_SOURCE_DIR "/captures/boxes-orbit";
  std::string cache = "bench-captures";
  bool floor = false;
  bool rates = true;
  std::string floorJson;
  int rateMib = 256;
  std::pair<int, int> rateSize{3840, 2160};
  CostMeasure cost = CostMeasure::Time;
  std::vector<std::string> timedOnlyFlags;  // given flags that counts refuse
};

struct Config {
  const Technique* technique = nullptr;
  std::string preset;               // "" for a technique without presets
  std::vector<std::string> assignments;
  int width = 0, height = 0;
  std::string label() const {
    std::string name = technique->name + (preset.empty() ? "" : "/" + preset);
    for (const auto& a : assignments) {
      std::string part = a;
      std::replace(part.begin(), part.end(), '=', ':');
      name += "/" + part;
    }
    return fmt::format("{}/{}x{}", name, width, height);
  }
  std::string key() const { return label(); }
};

struct Measured {
  std::map<std::string, std::vector<double>> passMs;  // per pass, one sample per timed execution (counted: the count)
  std::vector<double> pipelineMs;                      // repetitionSumsMs: the compute passes, per execution
};

bool counted(const Options& o) { return o.cost != CostMeasure::Time; }

class Harness {
 public:
  explicit Harness(Options o) : options_(std::move(o)), source_(loadCapture(options_.capture)), context_({options_.device, false}) {
    prepareCountedContext(context_.vk, options_.cost);
  }
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

  // The settings of a configuration on `capture` (the radius is the capture's unless assigned).
  Settings settings(const Config& config, const Capture& capture) const {
    Settings s = resolveSettings(*config.technique, capture, config.preset, config.assignments);
    if (options_.extraSlices && s.has("slices")) s.set("slices", s.value("slices") + options_.extraSlices);
    return s;
  }

  // The passes a configuration's second frame runs (history valid), from its graph compiled without
  // a device: what to register a series for.
  std::vector<std::string> livePasses(const Config& config) const {
    Settings s = settings(config, source_);
    FrameBuilder::Setup setup;
    setup.settings = &s;
    const auto& frame = source_.frames.front();
    // Frame 1 of a still camera, after frame 0 (built first, as a replay would, so that a technique
    // that keeps state per frame, rtao's accumulation, knows frame 0).
    setup.camera = FrameCamera{frame.view, frame.projection, config.width, config.height, 1};
    setup.previousCamera = FrameCamera{frame.view, frame.projection, config.width, config.height, 0};
    setup.capture = {source_.hasNormals, source_.hasDepth2 && config.technique->inputs.depth2 != InputUse::Unused};
    setup.historyWanted = setup.historyValid = historyNeedsOf(s, 2).keeps;
    std::unique_ptr<TechniqueState> state;
    if (config.technique->prepare) state = config.technique->prepare(ReplaySetup{source_, s, nullptr});
    setup.state = state.get();
    VulkanContext noDevice;
    PipelineCache pipelines(noDevice);
    FrameBuilder::Setup first = setup;
    first.camera = first.previousCamera = setup.previousCamera;
    first.historyValid = false;
    auto builtFrame = buildSteadyStateFrame(pipelines, first, setup);
    auto compiled = builtFrame.graph.compile();
    std::vector<std::string> names;
    for (const auto& p : compiled.passes) names.push_back(builtFrame.graph.passes()[p.pass].name);
    return names;
  }

  const Measured& measure(const Config& config) {
    auto found = measured_.find(config.key());
    if (found != measured_.end()) return found->second;
    if (counted(options_)) return measured_.emplace(config.key(), countCost(config)).first->second;
    Capture capture = resampledCapture(options_.capture, config.width, config.height, 2, options_.cache);
    ReplayOptions replay(settings(config, capture));
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
    // The run total's definition (report/gpu_total.h): Google Benchmark's median of these
    // samples is the frame's totalMedianMs.
    m.pipelineMs = repetitionSumsMs({timedFrame(frame)}, PassGroup::Compute);
    return measured_.emplace(config.key(), std::move(m)).first->second;
  }

  // Counted cost: one replay of frames 0:2 after a warm-up; frame 1's count of each pass, and
  // the compute passes' sum as `pipeline`.
  Measured countCost(const Config& config) {
    Capture capture = resampledCapture(options_.capture, config.width, config.height, 2, options_.cache);
    ReplayOptions replay(settings(config, capture));
    replay.frameBegin = 0;
    replay.frameEnd = 2;
    prepareCountedReplay(options_.cost, {}, replay);
    auto result = replayCapture(context_.vk, capture, replay, nullptr);
    Measured m;
    double pipeline = 0;
    for (const auto& pass : result.frames.back().passes) {
      const double count = costOf(options_.cost, pass.counts);
      m.passMs[pass.name] = {count};
      if (!isHostCopyPass(pass.name)) pipeline += count;
    }
    m.pipelineMs = {pipeline};
    return m;
  }

  // Frame 1's counts per live pass (history valid), from one replay of frames 0:2 through the
  // counting build.
  std::vector<DispatchCounts> count(const Config& config) {
    Capture capture = resampledCapture(options_.capture, config.width, config.height, 2, options_.cache);
    ReplayOptions replay(settings(config, capture));
    replay.frameBegin = 0;
    replay.frameEnd = 2;
    OpCounter counter(context_.vk);
    struct Counting {
      VulkanContext& vk;
      ~Counting() { vk.opCounter = nullptr; }
    } counting{context_.vk};
    context_.vk.opCounter = &counter;
    replayCapture(context_.vk, capture, replay, nullptr);
    return lastFramePerPass(counter.dispatches(), livePasses(config));
  }

  VulkanContext& vk() { return context_.vk; }

 private:
  Options options_;
  Capture source_;
  ContextScope context_;
  std::map<std::string, Measured> measured_;
};

Harness* harness = nullptr;
std::vector<Config> floorConfigs;  // every configuration registered by registerConfig, in order

// A counted repetition: real_time holds the count (manual time in "ms"), a counter names it.
void labelCount(benchmark::State& state, double count) {
  const std::string measure = costMeasureName(harness->options().cost);
  state.counters[measure] = count;
  state.SetLabel(measure + " counted under callgrind (real_time holds the count, not ms)");
}

// One benchmark = one series of samples; repetition i reports sample i as manual time.
void registerSeries(const std::string& name, Config config, std::string pass) {
  auto next = std::make_shared<size_t>(0);
  benchmark::RegisterBenchmark(name.c_str(), [config, pass, next](benchmark::State& state) {
    const auto& m = harness->measure(config);
    auto found = m.passMs.find(pass);
    if (pass != "pipeline" && found == m.passMs.end()) {
      state.SkipWithError(("pass " + pass + " did not run").c_str());
      return;
    }
    const auto& samples = pass == "pipeline" ? m.pipelineMs : found->second;
    const double sample = samples.at(*next % samples.size());
    for (auto _ : state) state.SetIterationTime(sample / 1000.0);
    ++*next;
    state.counters["pixels"] = double(config.width) * double(config.height);
    if (counted(harness->options())) labelCount(state, sample);
  })
      ->UseManualTime()
      ->Iterations(1)
      ->Repetitions(counted(harness->options()) ? 1 : harness->options().reps)
      ->Unit(benchmark::kMillisecond);
}

void registerConfig(const Config& config) {
  floorConfigs.push_back(config);
  registerSeries("pipeline/" + config.label(), config, "pipeline");
  for (const auto& pass : harness->livePasses(config)) registerSeries(pass + "/" + config.label(), config, pass);
}

// Slices x steps beyond the presets, at one size, for the scaling fit.
const std::vector<std::pair<int, int>> kScalingSliceSteps{{1, 2}, {2, 2}, {2, 4}, {3, 3}, {4, 4}, {9, 3}, {6, 6}};

std::pair<int, int> scalingSize() {
  const auto& o = harness->options();
  return o.scalingSize ? *o.scalingSize : o.sizes.size() > 1 ? o.sizes[1] : o.sizes[0];
}

bool scales(const Technique& t) { return t.parameter("slices") && t.parameter("steps"); }

// The scaling fit's configurations: the default preset with each of kScalingSliceSteps, at
// scalingSize(), for the first technique with slices and steps. Registration and the fit both take
// them from here.
std::vector<Config> scalingConfigs() {
  auto [w, h] = scalingSize();
  std::vector<Config> configs;
  for (const auto& name : harness->options().techniques) {
    const Technique& t = findTechnique(name);
    if (!scales(t)) continue;
    for (auto [slices, steps] : kScalingSliceSteps)
      configs.push_back({&t, t.defaultPreset, {fmt::format("slices={}", slices), fmt::format("steps={}", steps)}, w, h});
    break;
  }
  return configs;
}

std::vector<std::string> presetsOf(const Technique& t) {
  const auto& o = harness->options();
  std::vector<std::string> names;
  if (t.presets.empty()) return {""};
  for (const auto& p : t.presets)
    if (o.presets.empty() || std::count(o.presets.begin(), o.presets.end(), p.name)) names.push_back(p.name);
  return names;
}

void registerAll() {
  const auto& o = harness->options();
  for (auto [w, h] : o.sizes)
    for (const auto& name : o.techniques) {
      const Technique& t = findTechnique(name);
      for (const auto& preset : presetsOf(t)) registerConfig({&t, preset, {}, w, h});
      for (const auto& extra : o.extras) registerConfig({&t, t.defaultPreset, extra, w, h});
    }
  if (counted(o)) return;  // the scaling fit is of milliseconds
  for (const auto& c : scalingConfigs()) registerSeries("pipeline/" + c.label(), c, "pipeline");
}

ScalingInput scalingInput() {
  const auto& o = harness->options();
  ScalingInput in;
  const Technique& first = findTechnique(o.techniques.front());
  // Only what the benchmark filter let run.
  for (auto [w, h] : o.sizes)
    if (const auto* m = harness->alreadyMeasured({&first, first.defaultPreset, {}, w, h}))
      in.byPixels.push_back({double(w) * h, summarize(m->pipelineMs).median});
  auto configs = scalingConfigs();  // in the order of kScalingSliceSteps
  for (size_t i = 0; i < configs.size(); ++i)
    if (const auto* m = harness->alreadyMeasured(configs[i])) {
      auto [slices, steps] = kScalingSliceSteps[i];
      in.bySliceSteps.push_back({double(slices * steps), summarize(m->pipelineMs).median});
    }
  auto [w, h] = scalingSize();
  in.sliceStepsSize = fmt::format("{}x{}", w, h);
  return in;
}

CostMeasure parseCostMeasure(const std::string& name) {
  if (auto measure = costMeasureNamed(name)) return *measure;
  throw InputError("", std::nullopt, "--cost", fmt::format("'{}' is not time, instructions or cycles", name));
}

std::vector<std::string> splitList(const std::string& s, char separator = ',') {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, separator);) out.push_back(item);
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
    else if (auto t = value("--technique")) o.techniques = splitList(*t);
    else if (auto x = value("--extra")) o.extras.push_back(splitList(*x, ';'));
    else if (auto r = value("--reps")) o.reps = parseInt(*r, "--reps", 5, 100000);  // compare needs 5 a side
    else if (auto wu = value("--warmup")) o.warmup = parseInt(*wu, "--warmup", 0, 100000);
    else if (auto wm = value("--warmup-ms")) o.warmupMs = parseNumber(*wm, "--warmup-ms", 0.0, 600000.0);
    else if (auto es = value("--extra-slices")) o.extraSlices = parseInt(*es, "--extra-slices", 0, 23);
    else if (auto d = value("--device")) o.device = *d;
    else if (auto c = value("--capture")) o.capture = *c;
    else if (auto c2 = value("--cache")) o.cache = *c2;
    else if (arg == "--floor") o.floor = true;
    else if (arg == "--no-rates") o.rates = false;
    else if (auto fj = value("--floor-json")) o.floorJson = *fj;
    else if (auto rm = value("--rate-mib")) o.rateMib = parseInt(*rm, "--rate-mib", 1, 4096);
    else if (auto rs = value("--rate-size")) o.rateSize = parseSize(*rs, "--rate-size");
    else if (auto cm = value("--cost")) o.cost = parseCostMeasure(*cm);
    else argv[kept++] = argv[i];
    for (const char* timedOnly : {"--reps", "--warmup", "--warmup-ms", "--floor"})
      if (arg == timedOnly || arg.starts_with(std::string(timedOnly) + "=")) o.timedOnlyFlags.push_back(timedOnly);
  }
  argc = kept;
  if (counted(o) && !o.timedOnlyFlags.empty())
    throw InputError("", std::nullopt, o.timedOnlyFlags.front(),
                     fmt::format("--cost={} counts each configuration once without a clock to warm up; {} is for time",
                                 costMeasureName(o.cost), o.timedOnlyFlags.front()));
  for (const auto& t : o.techniques) findTechnique(t);  // an unknown name is bad usage: exit 2
  return o;
}

// --floor: counts of every registered configuration, the device's rates, and the table.
void reportFloor() {
  const auto& o = harness->options();
  std::optional<DeviceRates> rates;
  if (o.rates) rates = measureDeviceRates(harness->vk(), uint64_t(o.rateMib) << 20, o.rateSize, 20, o.warmupMs);
  std::vector<PassFloor> rows;
  for (const auto& config : floorConfigs) {
    const Measured* m = harness->alreadyMeasured(config);
    for (const auto& counts : harness->count(config)) {
      std::optional<double> ms;
      if (m)
        if (auto found = m->passMs.find(counts.pass); found != m->passMs.end()) ms = summarize(found->second).median;
      rows.push_back(passFloor(config.label(), counts, rates ? &*rates : nullptr, ms));
    }
  }
  printFloorTable(stdout, rows, rates ? &*rates : nullptr);
  if (!o.floorJson.empty()) {
    std::ofstream out(o.floorJson);
    out << floorJson(rows, rates ? &*rates : nullptr, harness->device().name).dump(1) << "\n";
    if (!out) throw std::runtime_error("cannot write " + o.floorJson);
  }
}

}  // namespace
}  // namespace aor::bench

int main(int argc, char** argv) {
  using namespace aor::bench;
  try {
    aor::rememberCommandLine(argc, argv);  // counted cost re-executes it under callgrind
    Options options = parseOwnFlags(argc, argv);
    if (counted(options) && !aor::CallgrindCounter::underCallgrind()) return aor::runUnderCallgrind(options.cost);
    Harness h(std::move(options));
    harness = &h;
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 2;
    benchmark::AddCustomContext("vulkan_device", h.device().name);
    benchmark::AddCustomContext("vulkan_driver", h.device().driver);
    if (counted(h.options()))
      benchmark::AddCustomContext("aoreplay_cost", aor::costDependencies(h.options().cost, h.device()).dump());
    registerAll();
    benchmark::RunSpecifiedBenchmarks();
    if (!counted(h.options())) printScaling(stderr, scalingInput());
    if (h.options().floor) reportFloor();
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
