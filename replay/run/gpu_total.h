#pragma once
// The one definition of a run's GPU total, used by the run table, report.json's
// gpu_ms_total_median, `aoreplay compare`'s total, sweep's total and ao_bench's `pipeline`:
// for every timed repetition of every frame, the sum of the compute passes' durations in that
// repetition (the harness's upload and read-back copies are left out); the run's total is the
// median of those sums.
//
// Why this and not the sum of the passes' medians: a per-repetition sum is a frame time that was
// measured (a sum of medians mixes repetitions, so it is the time of no repetition), it is what
// ao_bench's `pipeline` has always reported (one sample per execution, the median taken by Google
// Benchmark), and it has samples: `compare` can test a run's sums against another run's, and take
// their median as the run's one value when it judges runs.
#include <string>
#include <vector>

namespace aor {

// One pass of one frame: its duration in every timed repetition of the frame, in order.
struct TimedPass {
  std::string name;
  std::vector<double> durationsMs;
};
using TimedFrame = std::vector<TimedPass>;  // the frame's live passes

// Which passes a sum adds up: the pipeline's compute passes, or the harness's host copies.
enum class PassGroup { Compute, HostCopies };

// Per frame (in order), per timed repetition: the sum of the group's passes in that repetition,
// frame-major like report.json's passes[].gpu_ms.samples. A frame without passes of the group
// adds nothing. Throws std::invalid_argument when one frame's passes have different repetition
// counts (the sums would add durations of different repetitions).
std::vector<double> repetitionSumsMs(const std::vector<TimedFrame>& frames, PassGroup group = PassGroup::Compute);

// The total: the median of repetitionSumsMs; 0 when nothing of the group was timed.
double totalMedianMs(const std::vector<TimedFrame>& frames, PassGroup group = PassGroup::Compute);

}  // namespace aor
