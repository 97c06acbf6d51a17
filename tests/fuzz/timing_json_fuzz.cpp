// libFuzzer target for `aoreplay compare`'s inputs: the input is one report.json or Google
// Benchmark JSON file. It is read with aor::loadTimingSamples and, when valid, compared with itself
// (compareTimings, the table and the JSON verdicts), as compare does. Bad input must end in
// aor::InputError; a crash, any other exception, a sanitizer report or a disagreement of the
// bounded parser's two paths is a finding.
#include <cstddef>
#include <cstdint>

#include "json_fuzz_support.h"
#include "report/compare.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  aor::fuzz::checkBothParsersAgree(data, size, aor::JsonLimits{std::uint64_t(256) << 20, 10'000'000, 128});
  const auto file = aor::fuzz::inputFile("timings.json", data, size);
  try {
    const auto samples = aor::loadTimingSamples(file);
    const aor::CompareOptions options;
    const auto comparison = aor::compareTimings(samples, samples, options);
    (void)aor::comparisonTable(comparison);
    (void)aor::comparisonJson(comparison, options).dump();
  } catch (const aor::InputError&) {
    // The expected outcome for malformed input.
  }
  return 0;
}
