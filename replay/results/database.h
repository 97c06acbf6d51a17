#pragma once
// The small interface the results store is written against (replay/results/README.md): SQL text
// with `?` placeholders, typed parameters and rows, one write transaction at a time, and the
// schema version. SQLite (SQLiteCpp) and PostgreSQL (libpqxx) implement it; schema.cpp and
// store.cpp hold the only SQL, the same for both.
#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <memory>
#include <string>
#include <variant>
#include <vector>

namespace aor::results {

using SqlValue = std::variant<std::nullptr_t, std::int64_t, double, std::string>;

// One row of a query's result, read by column index as the type the caller expects.
class Row {
 public:
  virtual ~Row() = default;
  virtual bool isNull(int column) const = 0;
  virtual std::int64_t integer(int column) const = 0;
  virtual double real(int column) const = 0;
  virtual std::string text(int column) const = 0;
};

enum class Dialect { Sqlite, Postgres };

class Database {
 public:
  virtual ~Database() = default;
  virtual Dialect dialect() const = 0;
  // Runs one statement; `onRow` sees each result row.
  virtual void query(const std::string& sql, const std::vector<SqlValue>& parameters,
                     const std::function<void(const Row&)>& onRow) = 0;
  void execute(const std::string& sql, const std::vector<SqlValue>& parameters = {}) {
    query(sql, parameters, [](const Row&) {});
  }
  // The first column of the first row, when there is one.
  std::optional<std::int64_t> integerOrNone(const std::string& sql, const std::vector<SqlValue>& parameters);
  // A write transaction that holds the store's write lock from its start (SQLite BEGIN IMMEDIATE;
  // PostgreSQL BEGIN and an advisory lock when `exclusive`), so concurrent writers take turns
  // instead of failing half-way.
  virtual void beginWrite(bool exclusive) = 0;
  virtual void commit() = 0;
  virtual void rollback() = 0;
  // The schema version (SQLite PRAGMA user_version; PostgreSQL a one-row table), inside the
  // write transaction for setSchemaVersion.
  virtual int schemaVersion() = 0;
  virtual void setSchemaVersion(int version) = 0;
  // What messages call the store: the URL without a password.
  virtual std::string displayName() const = 0;
};

// `postgresql://...` or `postgres://...` (libpq's URL form) is a PostgreSQL server; `sqlite:PATH`
// or any other text is the path of an SQLite file, created when missing if `create` (record), else
// refused (trend, export). Throws InputError for a store that cannot be opened (naming it) and
// StoreError for the server's errors.
std::unique_ptr<Database> openDatabase(const std::string& url, bool create);

// A store's error (busy past the timeout, a server gone, a constraint): exit 1, not bad input.
struct StoreError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Rolls back on scope exit unless committed: an exception never leaves a transaction open.
class WriteTransaction {
 public:
  WriteTransaction(Database& db, bool exclusive) : db_(db) { db_.beginWrite(exclusive); }
  ~WriteTransaction() {
    if (!done_) try {
        db_.rollback();
      } catch (...) {
      }
  }
  void commit() {
    db_.commit();
    done_ = true;
  }
  WriteTransaction(const WriteTransaction&) = delete;
  WriteTransaction& operator=(const WriteTransaction&) = delete;

 private:
  Database& db_;
  bool done_ = false;
};

}  // namespace aor::results
