#pragma once
// An AO technique as a module (Falcor's render-pass plug-ins, Granite's per-effect setup functions,
// one XeGTAO.h per technique): one folder of C++ under replay/techniques/NAME/ and one of shaders
// under shaders/NAME/, registered by one line in registry.cpp. It declares its name and seed, its
// parameters and presets, the capture inputs it needs and what it does without them, its passes
// (added to each frame's render graph through a FrameBuilder, reading the shared front and writing
// the final visibility), its history, and how it runs without history. The host (replay, CLI,
// sweep, graph, bench, report) works from these declarations for every technique alike.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "technique_api/parameters.h"

namespace aor {

class FrameBuilder;
class Settings;
struct Capture;
struct DeviceInfo;
struct VulkanContext;

struct Preset {
  std::string name;
  std::vector<std::pair<std::string, double>> values;  // keys the preset sets; the rest keep their defaults
};

enum class InputUse { Unused, Optional, Required };

// Capture inputs beyond depth (which every technique reads) and what the technique does without them.
struct InputNeeds {
  InputUse normals = InputUse::Optional;  // without: normals reconstructed from depth (FrameBuilder::viewNormals)
  InputUse depth2 = InputUse::Unused;     // the second depth layer
};

struct DebugView {
  std::string name;  // --debug NAME, written as debug/NAME/NNNN.exr and .png
  std::string doc;
};

// What the technique keeps from one frame to the next, for the settings of a run.
struct HistoryNeeds {
  bool keeps = false;     // it declares history images (FrameBuilder::history)
  bool distance = false;  // it reads last frame's linear distance (FrameBuilder::previousDistance)
  std::string whyNot;     // when it keeps none: the setting behind that ("temporal=0"), for reset reasons
  // Where the output is an exponential moving average over frames (seed 000's temporal block): the
  // weight of last frame's output. The temporal metrics predict ghosting from it; 0: no such average.
  float blendWeight = 0.0f;
};

// What a technique keeps for a whole replay beyond history images (a BVH, compiled user shaders):
// made once by Technique::prepare, reached from each frame through FrameBuilder::state().
struct TechniqueState {
  virtual ~TechniqueState() = default;
  // What report.json's `technique_state` records of it (a BVH's size and build time), by key.
  virtual std::vector<std::pair<std::string, double>> reportValues() const { return {}; }
};

// What a technique's prepare() sees: the capture and settings of the replay, and the device when
// there is one (null for `aoreplay graph`, which compiles frames without running them).
struct ReplaySetup {
  const Capture& capture;
  const Settings& settings;
  VulkanContext* vk = nullptr;
};

// What the stress suite holds a technique to beyond outputs that are finite, in [0,1] and replay
// bit-identically (tests/techniques/stress_test.cpp runs every registered technique through it).
struct AccuracyBounds {
  // Mean visibility of a flat floor's surface seen at 1 degree grazing: a plane occludes nothing, so
  // 1 is exact; how far below that the technique's sampling and precision may land.
  double grazingPlaneMeanVisibility = 0.98;
};

struct Technique {
  std::string name;     // --technique NAME; [a-z][a-z0-9_]*
  std::string seed;     // the system it implements ("000 GTAO three-pass pipeline"), or "" for tools
  std::string summary;  // one line for `aoreplay techniques` and --help
  std::vector<Parameter> parameters;  // every key, in the order help and reports list them
  std::vector<Preset> presets;        // may be empty: the technique then runs once, with its defaults
  std::string defaultPreset;          // one of presets, or "" when there are none
  InputNeeds inputs;
  std::vector<DebugView> debugViews;
  AccuracyBounds bounds;
  // The FrameBuilder::reportValue key holding the samples per pixel a frame's output averages
  // (accumulated over frames), when it has one: sweep shows its range. Empty: none.
  std::string samplesValue;
  bool testOnly = false;  // registered by tests, never listed to users
  std::string file;       // a user technique's technique.json as --technique named it; empty for built-ins

  // Adds the technique's passes to the frame (after the shared front) and sets its output.
  std::function<void(FrameBuilder& frame, const Settings& settings)> addPasses;
  // History it keeps under `settings` (default: none).
  std::function<HistoryNeeds(const Settings& settings)> history;
  // The same technique without history, for the no-history replay temporal metrics compare against
  // when a capture has no references. Empty (or returning nullopt): it has none, and its runs get no
  // ghosting metrics.
  std::function<std::optional<Settings>(const Settings& settings)> withoutHistory;
  // Settings a capture cannot take (a second-layer path on a capture without one): throws InputError.
  std::function<void(const Settings& settings, const Capture& capture)> checkCapture;
  // Device extensions the settings need that `device` lacks (empty: it can run); the replay exits
  // 3 naming them.
  std::function<std::vector<std::string>(const Settings& settings, const DeviceInfo& device)> missingDeviceExtensions;
  // Optional device extensions (vk/context.h) the settings would use on `device` when it offers
  // them (rtao's ray queries): the command's context enables them. Empty: none.
  std::function<std::vector<std::string>(const Settings& settings, const DeviceInfo& device)> deviceExtensions;
  // Checks the passes' shaders against `device`'s limits (vk/device_limits.h) before any GPU work:
  // throws InputError naming the pass, the limit and the value. Built-ins leave it empty (their
  // pipelines are still checked when created).
  std::function<void(const DeviceInfo& device)> checkDeviceLimits;
  // Per-replay state (optional).
  std::function<std::unique_ptr<TechniqueState>(const ReplaySetup& setup)> prepare;

  const Parameter* parameter(std::string_view key) const;
  const Preset* preset(std::string_view name) const;
  const DebugView* debugView(std::string_view name) const;
  std::string keyList() const;     // "radius, slices, steps, ..."
  std::string tunableKeyList() const;  // the keys `aoreplay tune` searches by default, or "(none)"
  std::string presetList() const;  // "low, medium, high, ultra" or "(none)"
};

// Technique::deviceExtensions of every settings in `runs`, as ContextOptions::optionalExtensions
// takes them (a command that replays several techniques enables what any of them uses).
std::function<std::vector<std::string>(const DeviceInfo& device)> optionalExtensionsOf(std::vector<Settings> runs);

}  // namespace aor
