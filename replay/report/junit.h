#pragma once
// JUnit XML for CI systems (GitLab, Jenkins, GitHub test reporters): `run --expect`, `compare`
// and `ab` write one test case per checked metric or judged pass with --junit FILE.
#include <optional>
#include <string>
#include <vector>

#include "report/compare.h"
#include "report/expectations.h"

namespace aor {

struct JunitCase {
  std::string className;  // e.g. "aoreplay.expect"
  std::string name;
  std::optional<std::string> failure;  // the failure message (first line) and details
  bool skipped = false;                // shown, not judged
  std::string detail;                  // system-out text
};

// A <testsuites> document with one <testsuite> named `suite`.
std::string junitXml(const std::string& suite, const std::vector<JunitCase>& cases);

// One case per threshold; a failing one lists every frame (or the run) that broke it.
std::vector<JunitCase> expectationCases(const std::vector<Threshold>& thresholds, const std::vector<ExpectationFailure>& failures);
// One case per compared name: failed when slower (or unknown with --fail-on-unknown), skipped when not judged.
std::vector<JunitCase> comparisonCases(const Comparison& comparison, const CompareOptions& options);

}  // namespace aor
