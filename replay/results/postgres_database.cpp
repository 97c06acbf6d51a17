#include "results/postgres_database.h"

#include <charconv>
#include <optional>

#include <fmt/format.h>
#include <pqxx/pqxx>

#include "core/input_error.h"

namespace aor::results {
namespace {

// Every writer of one store takes this transaction-scoped advisory lock first (for the schema's
// migrations), so two first-time recorders never create the tables at once.
constexpr std::int64_t kMigrationLockKey = 0x616f7265706c6179;  // "aoreplay"

// The URL as messages show it: without the password.
std::string withoutPassword(const std::string& url) {
  auto scheme = url.find("://");
  auto at = url.find('@');
  if (scheme == std::string::npos || at == std::string::npos) return url;
  auto colon = url.find(':', scheme + 3);
  if (colon == std::string::npos || colon > at) return url;
  return url.substr(0, colon) + ":***" + url.substr(at);
}

class PostgresRow final : public Row {
 public:
  explicit PostgresRow(const pqxx::row& row) : row_(row) {}
  bool isNull(int column) const override { return row_[column].is_null(); }
  std::int64_t integer(int column) const override { return row_[column].as<std::int64_t>(); }
  // float8's text is the shortest form that reads back to the same double (PostgreSQL 12 and later).
  double real(int column) const override {
    std::string_view text = row_[column].c_str();
    double value = 0;
    auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size())
      throw StoreError(fmt::format("not a number in a float column: {}", text));
    return value;
  }
  std::string text(int column) const override { return row_[column].as<std::string>(); }

 private:
  const pqxx::row& row_;
};

// `?` placeholders as PostgreSQL's $1, $2, ... (the store's SQL has no `?` inside string literals).
std::string numberedPlaceholders(const std::string& sql) {
  std::string out;
  int n = 0;
  for (char c : sql) out += c == '?' ? fmt::format("${}", ++n) : std::string(1, c);
  return out;
}

class PostgresDatabase final : public Database {
 public:
  explicit PostgresDatabase(const std::string& url) : url_(url), connection_(url) {}
  Dialect dialect() const override { return Dialect::Postgres; }

  void query(const std::string& sql, const std::vector<SqlValue>& parameters,
             const std::function<void(const Row&)>& onRow) override {
    std::vector<std::optional<std::string>> texts;
    for (const auto& p : parameters)
      texts.push_back(std::visit(
          [](const auto& v) -> std::optional<std::string> {
            using T = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<T, std::nullptr_t>) return std::nullopt;
            else if constexpr (std::is_same_v<T, std::string>) return v;
            else if constexpr (std::is_same_v<T, double>) return fmt::format("{}", v);  // shortest round trip
            else return fmt::format("{}", v);
          },
          p));
    std::vector<const char*> pointers;
    for (const auto& t : texts) pointers.push_back(t ? t->c_str() : nullptr);
    try {
      pqxx::result result;
      std::string numbered = numberedPlaceholders(sql);
      if (transaction_) {
        result = transaction_->exec_params(numbered, pqxx::prepare::make_dynamic_params(pointers));
      } else {
        pqxx::nontransaction once(connection_);
        result = once.exec_params(numbered, pqxx::prepare::make_dynamic_params(pointers));
      }
      for (const auto& row : result) onRow(PostgresRow(row));
    } catch (const pqxx::failure& e) {
      throw StoreError(fmt::format("{}: {}", displayName(), e.what()));
    }
  }
  void beginWrite(bool exclusive) override {
    transaction_ = std::make_unique<pqxx::work>(connection_);
    if (exclusive) execute("SELECT pg_advisory_xact_lock(?)", {kMigrationLockKey});
  }
  void commit() override {
    try {
      transaction_->commit();
    } catch (const pqxx::failure& e) {
      transaction_.reset();
      throw StoreError(fmt::format("{}: {}", displayName(), e.what()));
    }
    transaction_.reset();
  }
  void rollback() override {
    if (transaction_) transaction_->abort();
    transaction_.reset();
  }
  int schemaVersion() override {
    execute("CREATE TABLE IF NOT EXISTS aoreplay_schema (version INTEGER NOT NULL)");
    return int(integerOrNone("SELECT version FROM aoreplay_schema", {}).value_or(0));
  }
  void setSchemaVersion(int version) override {
    execute("DELETE FROM aoreplay_schema");
    execute("INSERT INTO aoreplay_schema (version) VALUES (?)", {std::int64_t(version)});
  }
  std::string displayName() const override { return withoutPassword(url_); }

 private:
  std::string url_;
  pqxx::connection connection_;
  std::unique_ptr<pqxx::work> transaction_;
};

}  // namespace

std::unique_ptr<Database> openPostgres(const std::string& url) {
  try {
    return std::make_unique<PostgresDatabase>(url);
  } catch (const pqxx::failure& e) {
    throw InputError(withoutPassword(url), std::nullopt, "--db", fmt::format("cannot connect: {}", e.what()));
  }
}

}  // namespace aor::results
