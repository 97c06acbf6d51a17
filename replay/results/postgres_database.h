#pragma once
#include <memory>
#include <string>

#include "results/database.h"

namespace aor::results {
// A PostgreSQL server through libpqxx; `url` is libpq's postgresql:// URL.
std::unique_ptr<Database> openPostgres(const std::string& url);
}  // namespace aor::results
