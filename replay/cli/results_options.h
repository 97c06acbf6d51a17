#pragma once
// What record, trend and export share: the store's URL, and commit dates.
#include <string>

#include <CLI/CLI.hpp>

namespace aor::cli {

// The default store: an SQLite file in the current folder.
inline constexpr const char* kDefaultStore = "aoreplay-results.sqlite";

void addStoreOption(CLI::App& command, std::string& url);

// Seconds since 1970 (UTC) of YYYY-MM-DD[THH:MM[:SS]][Z|+HH:MM|-HH:MM] or @SECONDS; InputError
// naming --date otherwise.
double parseCommitDate(const std::string& text);

}  // namespace aor::cli
