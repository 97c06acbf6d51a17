#pragma once
// Counted cost (docs/guide.md, "Counted cost"): on a CPU device every shader is machine code, so the work
// of a pass can be counted instead of timed. aoreplay re-executes itself under valgrind's
// callgrind with instrumentation off (cost/launcher.h); inside, a CallgrindCounter brackets
// each counted submission: the device's thread left to settle, counters zeroed and
// instrumentation on before it, off and a named dump after it. The dump is read (and removed) at
// once. Counts do not move with the machine's load.
//
// What is counted: every instruction of the pass's submission on lavapipe's threads (the JIT-compiled
// shaders, the driver's own code, the C library's copies), except the C library's allocator and
// thread synchronisation. Those two take paths that depend on what the heap and the other threads
// were doing (which free list a block comes from, whether a lock was contended), so they differ
// between processes by tens to hundreds of instructions a pass; without them counts are exact.
#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>

namespace aor {

enum class CostMeasure { Time, Instructions, Cycles };
inline constexpr std::array<CostMeasure, 3> kCostMeasures = {CostMeasure::Time, CostMeasure::Instructions,
                                                             CostMeasure::Cycles};
const char* costMeasureName(CostMeasure measure);  // "time", "instructions", "cycles"
// The measure a command line names, or nothing.
std::optional<CostMeasure> costMeasureNamed(std::string_view name);

// Callgrind's event counts: Ir, and with its cache simulation Dr, Dw, I1mr, D1mr, D1mw, ILmr,
// DLmr, DLmw.
using EventCounts = std::map<std::string, uint64_t>;

// The measure's value: instructions = Ir; cycles = L1 hits + 5 x last-level hits + 35 x memory
// accesses (the estimate iai-callgrind uses), from the cache simulation's events.
double costOf(CostMeasure measure, const EventCounts& counts);
inline constexpr const char* kCyclesFormula = "(Ir + Dr + Dw - L1 misses) + 5 x (L1 misses - LL misses) + 35 x LL misses";

// The cache geometry `cycles` pins on valgrind's command line (never detected from the host), so
// that runners with other caches count the same: I1, D1: 32 KiB, 8-way, 64-byte lines; LL:
// 8 MiB, 16-way, 64-byte lines.
inline constexpr const char* kCostCacheI1 = "32768,8,64";
inline constexpr const char* kCostCacheD1 = "32768,8,64";
inline constexpr const char* kCostCacheLL = "8388608,16,64";

// Whether a function of the C library (callgrind's name for it) is its allocator's or its thread
// synchronisation's: left out of counts.
bool isExcludedFromCounts(std::string_view function);

// The self cost of every function a callgrind dump holds, summed over the functions counts keep
// (a function of libc.so is left out when isExcludedFromCounts). Throws std::runtime_error for a
// dump it cannot read.
EventCounts countedEvents(const std::string& dumpText);

class CallgrindCounter {
 public:
  // `outFile`: the --callgrind-out-file valgrind was given (dump N goes to outFile.N).
  explicit CallgrindCounter(std::filesystem::path outFile) : outFile_(std::move(outFile)) {}
  static bool underCallgrind();
  void begin();
  EventCounts end(const std::string& name);

 private:
  std::filesystem::path outFile_;
};

// What the counts depend on beyond the build: the processor as the counted process sees it
// (cpuid's brand string: under valgrind, what LLVM's host detection sees), and the valgrind that
// counted (the launcher passes its version down).
std::string countedCpuName();
std::string countedValgrindVersion();
inline constexpr const char* kCostDumpsVariable = "AOREPLAY_COST_DUMPS";  // the --callgrind-out-file
inline constexpr const char* kCostValgrindVariable = "AOREPLAY_COST_VALGRIND";

}  // namespace aor
