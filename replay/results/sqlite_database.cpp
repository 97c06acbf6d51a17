#include "results/sqlite_database.h"

#include <chrono>
#include <thread>

#include <SQLiteCpp/SQLiteCpp.h>
#include <sqlite3.h>
#include <fmt/format.h>

#include "core/input_error.h"

namespace aor::results {
namespace {

// Long enough for three other CI jobs' transactions (each a few milliseconds to a second) to end.
constexpr int kBusyTimeoutMs = 60'000;

class SqliteRow final : public Row {
 public:
  explicit SqliteRow(SQLite::Statement& statement) : statement_(statement) {}
  bool isNull(int column) const override { return statement_.getColumn(column).isNull(); }
  std::int64_t integer(int column) const override { return statement_.getColumn(column).getInt64(); }
  double real(int column) const override { return statement_.getColumn(column).getDouble(); }
  std::string text(int column) const override { return statement_.getColumn(column).getString(); }

 private:
  SQLite::Statement& statement_;
};

class SqliteDatabase final : public Database {
 public:
  explicit SqliteDatabase(const std::filesystem::path& file)
      : file_(file), db_(file.string(), SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE, kBusyTimeoutMs) {
    // WAL: readers (trend) never block a writer (record) and a killed writer's transaction is
    // simply not in the log. While another process switches a new file to WAL, the switch answers
    // SQLITE_BUSY at once without calling the busy handler (a concurrent `record` on a fresh
    // store failed so once in six CI runs): it is retried for as long as any lock is waited for.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(kBusyTimeoutMs);
    for (;;) {
      try {
        db_.exec("PRAGMA journal_mode=WAL");
        break;
      } catch (const SQLite::Exception& e) {
        if ((e.getErrorCode() != SQLITE_BUSY && e.getErrorCode() != SQLITE_LOCKED) ||
            std::chrono::steady_clock::now() > deadline)
          throw;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
      }
    }
    db_.exec("PRAGMA foreign_keys=ON");
  }
  Dialect dialect() const override { return Dialect::Sqlite; }

  void query(const std::string& sql, const std::vector<SqlValue>& parameters,
             const std::function<void(const Row&)>& onRow) override {
    try {
      SQLite::Statement statement(db_, sql);
      for (size_t i = 0; i < parameters.size(); ++i) bind(statement, int(i + 1), parameters[i]);
      SqliteRow row(statement);
      while (statement.executeStep()) onRow(row);
    } catch (const SQLite::Exception& e) {
      // Damage found only when a page is read (the header and schema were fine at open) is the
      // file's fault, not the tool's: bad input, said plainly.
      if (e.getErrorCode() == SQLITE_CORRUPT || e.getErrorCode() == SQLITE_NOTADB)
        throw InputError(displayName(), std::nullopt, "--db",
                         fmt::format("the store is damaged ({}); restore it from a copy, or record into a new file", e.what()));
      throw StoreError(fmt::format("{}: {}", displayName(), e.what()));
    }
  }
  void beginWrite(bool) override { execute("BEGIN IMMEDIATE"); }  // the write lock now, or wait for it
  void commit() override { execute("COMMIT"); }
  void rollback() override { execute("ROLLBACK"); }
  int schemaVersion() override { return int(integerOrNone("PRAGMA user_version", {}).value_or(0)); }
  void setSchemaVersion(int version) override { execute(fmt::format("PRAGMA user_version = {}", version)); }
  std::string displayName() const override { return file_.string(); }

 private:
  static void bind(SQLite::Statement& statement, int index, const SqlValue& value) {
    std::visit(
        [&](const auto& v) {
          using T = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<T, std::nullptr_t>) statement.bind(index);
          else if constexpr (std::is_same_v<T, std::int64_t>) statement.bind(index, static_cast<int64_t>(v));
          else statement.bind(index, v);
        },
        value);
  }

  std::filesystem::path file_;
  SQLite::Database db_;
};

}  // namespace

std::unique_ptr<Database> openSqlite(const std::filesystem::path& file) {
  if (std::filesystem::is_directory(file))
    throw InputError(file.string(), std::nullopt, "--db", "is a folder, not an SQLite file");
  try {
    return std::make_unique<SqliteDatabase>(file);
  } catch (const SQLite::Exception& e) {
    throw InputError(file.string(), std::nullopt, "--db", fmt::format("cannot open as an SQLite store: {}", e.what()));
  }
}

}  // namespace aor::results
