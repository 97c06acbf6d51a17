#include "results/database.h"

#include <filesystem>

#include "core/input_error.h"

#include "results/postgres_database.h"
#include "results/sqlite_database.h"

namespace aor::results {

std::optional<std::int64_t> Database::integerOrNone(const std::string& sql, const std::vector<SqlValue>& parameters) {
  std::optional<std::int64_t> value;
  query(sql, parameters, [&](const Row& row) {
    if (!value && !row.isNull(0)) value = row.integer(0);
  });
  return value;
}

std::unique_ptr<Database> openDatabase(const std::string& url, bool create) {
  if (url.starts_with("postgresql://") || url.starts_with("postgres://")) return openPostgres(url);
  std::filesystem::path file = url.starts_with("sqlite:") ? url.substr(7) : url;
  if (file.empty())
    throw InputError(url, std::nullopt, "--db", "names no file: give sqlite:PATH, a file path or a postgresql:// URL");
  if (!create && !std::filesystem::exists(file))
    throw InputError(file.string(), std::nullopt, "--db", "no such store (aoreplay record creates one)");
  return openSqlite(file);
}

}  // namespace aor::results
