// libFuzzer target for `aoreplay run --expect FILE`: the input is the thresholds file. It is read
// with aor::loadExpectations and, when valid, held against a small report (checkExpectations), as
// a run does. Bad input must end in aor::InputError; a crash, any other exception, a sanitizer
// report or a disagreement of the bounded parser's two paths is a finding.
#include <cstddef>
#include <cstdint>

#include "json_fuzz_support.h"
#include "report/expectations.h"

namespace {

const nlohmann::json& report() {
  static const nlohmann::json r = nlohmann::json::parse(R"({
    "passes": [{"name": "gtao", "gpu_ms": {"median": 1.5}}],
    "metrics": {"error": {"rmse": 0.05}, "temporal": {"warping_error": 0.001, "disocclusion": {"response_frames": 3}}},
    "frames": [{"index": 0, "gpu_ms_median": {"gtao": 1.4}, "metrics": {"error": {"rmse": 0.04}}},
               {"index": 1, "gpu_ms_median": {"gtao": 1.6}, "metrics": {"error": {"rmse": 0.06}}}]})");
  return r;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  aor::fuzz::checkBothParsersAgree(data, size, aor::JsonLimits{std::uint64_t(1) << 20, 10'000, 128});
  const auto file = aor::fuzz::inputFile("expect.json", data, size);
  try {
    const auto thresholds = aor::loadExpectations(file);
    for (const auto& failure : aor::checkExpectations(thresholds, report(), file.string())) (void)failure.describe();
  } catch (const aor::InputError&) {
    // The expected outcome for malformed input.
  }
  return 0;
}
