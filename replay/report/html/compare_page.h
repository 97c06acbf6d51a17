#pragma once
// compare.html of `aoreplay compare --html FILE` and `aoreplay ab` (DIR/compare.html): per pass
// the verdict, both sides' values as strip plots with quartile boxes, and the threshold band a new
// median must leave to count as a change.
#include <string>

#include "report/compare.h"

namespace aor::html {

std::string comparePageHtml(const Comparison& comparison, const CompareOptions& options);

}  // namespace aor::html
