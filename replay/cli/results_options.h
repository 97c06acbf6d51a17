#pragma once
// What record, trend and export share: the store's URL, and commit dates.
#include <string>

#include <CLI/CLI.hpp>

namespace aor::cli {

// The default store: an SQLite file in the current folder.
inline constexpr const char* kDefaultStore = "aoreplay-results.sqlite";

void addStoreOption(CLI::App& command, std::string& url);

// A commit's position is stored as seconds (a date, or an ordinal N as N seconds after 1970), and
// every export prints it as an ISO date: positions outside 0001-01-01 .. 9999-12-31T23:59:59Z are
// refused when recorded, not stored to fail an export later.
inline constexpr long long kFirstPrintableSecond = -62135596800LL;
inline constexpr long long kLastPrintableSecond = 253402300799LL;

// Seconds since 1970 (UTC) of YYYY-MM-DD[THH:MM[:SS]][Z|+HH:MM|-HH:MM] or @SECONDS, inside the
// printable range; InputError naming --date otherwise.
double parseCommitDate(const std::string& text);

}  // namespace aor::cli
