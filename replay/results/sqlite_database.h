#pragma once
#include <filesystem>
#include <memory>

#include "results/database.h"

namespace aor::results {
// An SQLite file in WAL mode with a busy timeout: readers never block the writer, writers wait
// their turn (BEGIN IMMEDIATE) instead of failing.
std::unique_ptr<Database> openSqlite(const std::filesystem::path& file);
}  // namespace aor::results
