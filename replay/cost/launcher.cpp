#include "cost/launcher.h"

#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>

#include <fmt/format.h>

#include "core/input_error.h"
#include "core/output_directory.h"
#include "core/subprocess.h"

namespace aor {

namespace fs = std::filesystem;

namespace {

std::vector<std::string> gCommandLine;

// The first line valgrind prints for --version, or nothing when it cannot run.
std::optional<std::string> valgrindVersion() {
  FILE* pipe = popen("valgrind --version 2>/dev/null", "r");
  if (!pipe) return std::nullopt;
  char line[256] = {};
  const bool read = std::fgets(line, sizeof line, pipe) != nullptr;
  if (pclose(pipe) != 0 || !read) return std::nullopt;
  std::string version(line);
  while (!version.empty() && (version.back() == '\n' || version.back() == '\r')) version.pop_back();
  return version;
}

// What the count cost: the child's CPU time (it runs shaders on one thread, so under load its wall
// time grows and its CPU time does not), its wall time and the machine's load meanwhile.
void printChildCost(double wallSeconds) {
  struct rusage usage{};
  ::getrusage(RUSAGE_CHILDREN, &usage);
  auto seconds = [](const timeval& t) { return double(t.tv_sec) + double(t.tv_usec) * 1e-6; };
  double load[1] = {0};
  ::getloadavg(load, 1);
  std::fprintf(stderr, "counted under callgrind: %.1f s CPU (%.1f user + %.1f sys), %.1f s wall, load average %.2f\n",
               seconds(usage.ru_utime) + seconds(usage.ru_stime), seconds(usage.ru_utime), seconds(usage.ru_stime),
               wallSeconds, load[0]);
}

}  // namespace

void rememberCommandLine(int argc, char** argv) { gCommandLine.assign(argv, argv + argc); }

std::vector<std::string> callgrindArguments(CostMeasure measure, const std::string& outFile) {
  std::vector<std::string> args = {"valgrind", "--tool=callgrind", "--quiet", "--instr-atstart=no",
                                   "--callgrind-out-file=" + outFile};
  if (measure == CostMeasure::Cycles)
    args.insert(args.end(), {"--cache-sim=yes", std::string("--I1=") + kCostCacheI1,
                             std::string("--D1=") + kCostCacheD1, std::string("--LL=") + kCostCacheLL});
  return args;
}

int runUnderCallgrind(CostMeasure measure) {
  const auto version = valgrindVersion();
  if (!version)
    throw InputError("", std::nullopt, "--cost",
                     fmt::format("--cost {} counts under valgrind, which is not installed: apt-get install valgrind",
                                 costMeasureName(measure)));
  ScratchFolder dumps("aoreplay-cost");
  const std::string outFile = (dumps.path() / "callgrind.out").string();
  std::vector<std::string> argv = callgrindArguments(measure, outFile);
  argv.push_back(fs::read_symlink("/proc/self/exe").string());
  argv.insert(argv.end(), gCommandLine.begin() + 1, gCommandLine.end());
  const std::map<std::string, std::string> environment = {
      {"LP_NUM_THREADS", "0"},                // lavapipe's shaders on its queue thread alone
      {"MESA_SHADER_CACHE_DISABLE", "true"},  // every shader compiled the same way in each run
      {kCostDumpsVariable, outFile},
      {kCostValgrindVariable, *version}};
  std::fflush(stdout);
  std::fflush(stderr);
  const SpawnedProcess child = spawnProcess(argv, environment, "", "");
  if (child.pid < 0) throw std::runtime_error("cannot run valgrind: " + child.startError);
  forwardTerminationSignalsTo(child.pid);
  const auto start = std::chrono::steady_clock::now();
  const ProcessResult result = waitForProcess(child.pid, std::chrono::hours(24 * 365));
  forwardTerminationSignalsTo(0);
  printChildCost(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return result.signal ? 128 + result.signal : result.exitCode;
}

}  // namespace aor
