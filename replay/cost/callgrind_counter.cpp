#include "cost/callgrind_counter.h"

#include <cpuid.h>
#include <time.h>
#include <valgrind/callgrind.h>

#include <array>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace aor {

const char* costMeasureName(CostMeasure measure) {
  switch (measure) {
    case CostMeasure::Time: return "time";
    case CostMeasure::Instructions: return "instructions";
    case CostMeasure::Cycles: return "cycles";
  }
  return "?";
}

std::optional<CostMeasure> costMeasureNamed(std::string_view name) {
  for (CostMeasure m : kCostMeasures)
    if (name == costMeasureName(m)) return m;
  return std::nullopt;
}

namespace {

uint64_t event(const EventCounts& counts, const char* name) {
  auto it = counts.find(name);
  if (it == counts.end()) throw std::runtime_error(std::string("callgrind reported no ") + name + " events");
  return it->second;
}

std::vector<std::string> words(std::string_view line) {
  std::istringstream in{std::string(line)};
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

// glibc's allocator (malloc.c) and its locks, condition variables and futexes (nptl).
constexpr std::array<std::string_view, 30> kExcludedPrefixes = {
    "malloc", "free", "calloc", "realloc", "posix_memalign", "memalign", "aligned_alloc", "valloc", "pvalloc",
    "__libc_malloc", "__libc_free", "__libc_calloc", "__libc_realloc", "__libc_memalign", "_int_", "_mid_memalign",
    "unlink_chunk", "sysmalloc", "systrim", "alloc_perturb", "tcache", "arena_",
    "pthread_", "__pthread_", "_pthread_", "___pthread", "__lll_", "__futex", "futex", "__condvar"};

bool startsWithAny(std::string_view name, const auto& prefixes) {
  for (std::string_view p : prefixes)
    if (name.substr(0, p.size()) == p) return true;
  return false;
}

// "(12) name" defines id 12, "(12)" refers to it; a name without an id stands for itself.
std::string resolveName(std::string_view text, std::map<std::string, std::string>& names) {
  if (text.empty() || text[0] != '(') return std::string(text);
  size_t close = text.find(')');
  if (close == std::string_view::npos) throw std::runtime_error("callgrind dump: bad name " + std::string(text));
  std::string id(text.substr(1, close - 1));
  if (close + 1 < text.size()) names[id] = std::string(text.substr(close + 2));
  return names[id];
}

struct DumpReader {
  std::vector<std::string> events;
  size_t positions = 1;
  std::map<std::string, std::string> objects, functions;
  bool excluded = false, skipNextCost = false;
  std::string object, function;
  EventCounts counts;

  void costLine(std::string_view line) {
    if (skipNextCost) {  // a call's inclusive cost: the callee's own lines count it
      skipNextCost = false;
      return;
    }
    if (excluded) return;
    auto w = words(line);
    for (size_t i = positions; i < w.size() && i - positions < events.size(); ++i)
      counts[events[i - positions]] += std::stoull(w[i]);
  }
  void select() { excluded = object.find("libc.so") != std::string::npos && isExcludedFromCounts(function); }
  void line(std::string_view l) {
    auto after = [&](std::string_view key) { return l.substr(0, key.size()) == key; };
    if (after("events:")) events = words(l.substr(7));
    else if (after("positions:")) positions = words(l.substr(10)).size();
    else if (after("ob=")) object = resolveName(l.substr(3), objects), select();
    else if (after("fn=")) function = resolveName(l.substr(3), functions), select();
    else if (after("cob=")) resolveName(l.substr(4), objects);
    else if (after("cfn=") || after("cfi=") || after("cfl=")) {
      if (after("cfn=")) resolveName(l.substr(4), functions);
    } else if (after("calls=")) skipNextCost = true;
    else if (!l.empty() && (std::isdigit(static_cast<unsigned char>(l[0])) || l[0] == '+' || l[0] == '-' || l[0] == '*'))
      costLine(l);
  }
};

}  // namespace

double costOf(CostMeasure measure, const EventCounts& counts) {
  if (measure == CostMeasure::Instructions) return double(event(counts, "Ir"));
  const uint64_t accesses = event(counts, "Ir") + event(counts, "Dr") + event(counts, "Dw");
  const uint64_t l1Misses = event(counts, "I1mr") + event(counts, "D1mr") + event(counts, "D1mw");
  const uint64_t llMisses = event(counts, "ILmr") + event(counts, "DLmr") + event(counts, "DLmw");
  return double(accesses - l1Misses) + 5.0 * double(l1Misses - llMisses) + 35.0 * double(llMisses);
}

bool isExcludedFromCounts(std::string_view function) {
  function = function.substr(0, function.find_first_of("@'"));  // pthread_mutex_lock@@GLIBC_2.2.5, free'2
  return startsWithAny(function, kExcludedPrefixes);
}

EventCounts countedEvents(const std::string& dumpText) {
  DumpReader reader;
  std::istringstream in(dumpText);
  for (std::string line; std::getline(in, line);) reader.line(line);
  if (reader.events.empty()) throw std::runtime_error("callgrind's dump names no events");
  for (const auto& e : reader.events) reader.counts.try_emplace(e, 0);
  return reader.counts;
}

std::string countedCpuName() {
  unsigned regs[12] = {};
  for (unsigned leaf = 0; leaf < 3; ++leaf)
    if (!__get_cpuid(0x80000002 + leaf, &regs[4 * leaf], &regs[4 * leaf + 1], &regs[4 * leaf + 2], &regs[4 * leaf + 3]))
      return "unknown";
  char brand[49] = {};
  std::memcpy(brand, regs, 48);
  std::string name(brand);
  name.erase(0, name.find_first_not_of(' '));
  return name;
}

std::string countedValgrindVersion() {
  const char* version = std::getenv(kCostValgrindVariable);
  return version && *version ? version : "unknown";
}

bool CallgrindCounter::underCallgrind() { return RUNNING_ON_VALGRIND != 0; }

namespace {

// Under valgrind one thread runs at a time; sleeping hands the CPU to the device's queue thread
// until it blocks again, so it starts and ends every count in the same state.
void letTheDeviceThreadSettle() {
  struct timespec pause{0, 2'000'000};
  nanosleep(&pause, nullptr);
}

}  // namespace

// Collection is per thread in callgrind: the calling thread stops collecting while the device's
// queue thread (lavapipe runs command buffers on one of its own) does the pass, so the
// submission and the fence wait, whose paths vary with scheduling, are not counted.
void CallgrindCounter::begin() {
  letTheDeviceThreadSettle();
  CALLGRIND_ZERO_STATS;
  CALLGRIND_START_INSTRUMENTATION;
  CALLGRIND_TOGGLE_COLLECT;
}

EventCounts CallgrindCounter::end(const std::string& name) {
  letTheDeviceThreadSettle();
  CALLGRIND_TOGGLE_COLLECT;
  CALLGRIND_STOP_INSTRUMENTATION;
  CALLGRIND_DUMP_STATS_AT(name.c_str());
  // Callgrind numbers the dumps of a process 1, 2, ...: one count for every counter of the process
  // (a sweep replays several configurations, each with its own).
  static int dumps = 0;
  const std::filesystem::path dump = outFile_.string() + "." + std::to_string(++dumps);
  std::ifstream in(dump);
  if (!in) throw std::runtime_error("callgrind wrote no dump " + dump.string());
  std::stringstream text;
  text << in.rdbuf();
  in.close();
  std::filesystem::remove(dump);
  return countedEvents(text.str());
}

}  // namespace aor
