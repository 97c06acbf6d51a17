#pragma once
// `--cost time|instructions|cycles` of `run`, `sweep` and `ab` (docs/guide.md, "Counted cost").
#include <string>

#include <CLI/CLI.hpp>

#include "cost/callgrind_counter.h"

namespace aor::cli {

// --cost time|instructions|cycles, with `help` after the choices.
void addCostOption(CLI::App& command, CostMeasure& cost, const std::string& help);

}  // namespace aor::cli
