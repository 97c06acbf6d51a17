#pragma once
// The one check of every numeric command-line option: the whole text a finite number in
// [min, max] (options/number.h). CLI11's own Range lets "nan" through (every comparison with NaN
// is false), which once turned `compare --alpha nan` into a gate that never fails; "inf" and
// "1e999" are refused here too.
#include <string>

#include <CLI/CLI.hpp>

namespace aor::cli {

CLI::Validator numberIn(double min, double max);
CLI::Validator wholeIn(long long min, long long max);

}  // namespace aor::cli
