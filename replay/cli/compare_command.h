#pragma once
// What `aoreplay compare` and `aoreplay ab` share: the judging flags, and judging two sides.
#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "report/compare.h"

namespace aor::cli {

struct CompareFlags {
  std::string json;                 // --json FILE: the verdicts as JSON
  std::string html;                 // --html FILE: compare.html (compare only; ab writes DIR/compare.html)
  std::string junit;                // --junit FILE: one JUnit test case per compared name
  std::vector<std::string> ignore;  // --ignore REGEX...
  CompareOptions options;
  std::vector<std::string> timeOnlyGiven;  // time-only options given (--alpha, ...): refused with counts
};

// --json, --junit, --ignore, --alpha, --min-effect, --min-effect-ms, --spread-multiple, --judge-host-copies,
// --fail-on-unknown.
void addCompareFlags(CLI::App& command, CompareFlags& flags);

// The comparison of the two sides without the --ignore'd names. Throws InputError when no name is
// on both sides.
Comparison judgeSides(SideTimings baseline, SideTimings candidate, const CompareFlags& flags);

// Prints the table, writes --json, --junit and --html when given (never over one of `inputs`), and
// returns the exit status: 1 when the comparison fails (a judged name slower, or unknown with
// --fail-on-unknown), else 0.
int reportComparison(const Comparison& comparison, const CompareFlags& flags, const std::vector<std::filesystem::path>& inputs);

}  // namespace aor::cli
