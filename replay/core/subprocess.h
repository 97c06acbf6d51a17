#pragma once
// Runs a child program (the RenderDoc dump script's Python, `ab`'s runs) with its output sent to
// files and a time limit, so a child that crashes or hangs cannot take aoreplay with it. The child
// takes SIGINT, SIGTERM and SIGHUP as any program does and is killed when aoreplay ends.
#include <chrono>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace aor {

struct ProcessResult {
  bool started = false;  // false: the program could not be executed (startError says why)
  std::string startError;
  bool timedOut = false;  // killed after the time limit
  int exitCode = -1;      // when it exited
  int signal = 0;         // when a signal ended it
};

// `argv[0]` is looked up on PATH when it has no slash. `environment` adds to (or replaces in) the
// current environment. stdout and stderr go to the two files (one file when they are the same
// path; an empty path: aoreplay's own). Past `timeLimit` the child is killed (SIGKILL) and `timedOut` set.
ProcessResult runProcess(const std::vector<std::string>& argv, const std::map<std::string, std::string>& environment,
                         const std::filesystem::path& stdoutFile, const std::filesystem::path& stderrFile,
                         std::chrono::seconds timeLimit);

// The same start without waiting: the child's pid, or -1 with startError (and its errno) when it
// could not be executed. Descriptors without FD_CLOEXEC are inherited.
struct SpawnedProcess {
  int pid = -1;
  std::string startError;
  int startErrno = 0;
};
SpawnedProcess spawnProcess(const std::vector<std::string>& argv, const std::map<std::string, std::string>& environment,
                            const std::filesystem::path& stdoutFile, const std::filesystem::path& stderrFile);

// Waits for a spawned child; past `timeLimit` kills it (SIGKILL) and sets `timedOut`.
ProcessResult waitForProcess(int pid, std::chrono::milliseconds timeLimit);

// The last `lines` non-empty lines of a child's output file, joined with " | " for a one-line
// message ("(nothing)" when there are none).
std::string outputTail(const std::filesystem::path& file, size_t lines = 4);

}  // namespace aor
