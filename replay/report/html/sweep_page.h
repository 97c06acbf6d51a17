#pragma once
// sweep.html of `aoreplay sweep`: error against GPU time with the Pareto front, every
// configuration numbered (the plot's key, its hover text and the table share the numbers), and the
// table of configurations, sortable by any column.
#include <string>
#include <vector>

#include "report/sweep.h"

namespace aor::html {

std::string sweepPageHtml(const SweepInfo& info, const std::vector<SweepRow>& rows);

}  // namespace aor::html
