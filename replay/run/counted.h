#pragma once
// What a replay does differently inside callgrind (--cost instructions|cycles, of `run`, `sweep`
// and ao_bench): one counted run a frame after a warm-up, nothing of the tool's running
// meanwhile, and the options that make no sense with counts refused.
#include "cost/callgrind_counter.h"
#include "replay_loop/replayer.h"
#include "vk/context.h"

namespace aor {

struct TimedOnlyOptions {
  int repeat = 1;
  bool overlap = false;
  bool validate = false;
};

// Throws InputError naming --repeat (other than 1), --overlap or --validate; sets the replay's
// measure, dump file, isolated timing and at least one warm-up run.
void prepareCountedReplay(CostMeasure cost, const TimedOnlyOptions& given, ReplayOptions& options);
// The context a counted replay runs on: lavapipe (counts are its work on this CPU; another device
// is InputError, --device), settling after every submission. Nothing for `time`.
void prepareCountedContext(VulkanContext& vk, CostMeasure cost);

}  // namespace aor
