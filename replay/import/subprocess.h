#pragma once
// Runs a helper program (the RenderDoc dump script's Python) with its output sent to files and a
// time limit, so a helper that crashes or hangs on a bad file cannot take aoreplay with it.
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
// current environment. stdout and stderr go to the two files.
ProcessResult runProcess(const std::vector<std::string>& argv, const std::map<std::string, std::string>& environment,
                         const std::filesystem::path& stdoutFile, const std::filesystem::path& stderrFile,
                         std::chrono::seconds timeLimit);

}  // namespace aor
