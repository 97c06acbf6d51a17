#pragma once
// Counted cost's outer process: `run`, `sweep` and ao_bench with --cost instructions|cycles re-execute the same command
// under valgrind's callgrind (instrumentation off at start) in an environment that makes counts
// exact (one lavapipe thread, no shader disk cache), waits for it and passes its exit status on.
// The child does the whole run, holds --out's lock and writes every output; SIGINT, SIGTERM and
// SIGHUP sent to this process are passed on to it; its dumps go to a scratch folder removed after.
#include <string>
#include <vector>

#include "cost/callgrind_counter.h"

namespace aor {

// main() keeps the command line for the re-execution.
void rememberCommandLine(int argc, char** argv);

// Runs the remembered command under callgrind and returns its exit status (128 + N when signal N
// ended it). Throws InputError when valgrind is missing.
int runUnderCallgrind(CostMeasure measure);

// The valgrind arguments for `measure` (cache sizes pinned for cycles), before the program.
std::vector<std::string> callgrindArguments(CostMeasure measure, const std::string& outFile);

}  // namespace aor
