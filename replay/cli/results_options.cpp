#include "cli/results_options.h"

#include <cstdio>
#include <ctime>

#include <fmt/format.h>

#include "core/input_error.h"
#include "options/number.h"

namespace aor::cli {

void addStoreOption(CLI::App& command, std::string& url) {
  command.add_option("--db", url,
                     fmt::format("results store: an SQLite file (default {}) or postgresql://USER@HOST[:PORT]/DB", kDefaultStore));
}

double parseCommitDate(const std::string& text) {
  auto bad = [&] {
    return InputError("", std::nullopt, "--date",
                      fmt::format("{} is not YYYY-MM-DD[THH:MM[:SS]][Z|+HH:MM] or @SECONDS", text));
  };
  if (text.starts_with("@")) return double(parseLong(std::string_view(text).substr(1), "--date", kFirstPrintableSecond, kLastPrintableSecond));
  std::tm tm{};
  int used = 0;
  if (std::sscanf(text.c_str(), "%4d-%2d-%2d%n", &tm.tm_year, &tm.tm_mon, &tm.tm_mday, &used) != 3) throw bad();
  size_t at = size_t(used);
  if (at < text.size() && (text[at] == 'T' || text[at] == ' ')) {
    int n = 0;
    if (std::sscanf(text.c_str() + at + 1, "%2d:%2d%n", &tm.tm_hour, &tm.tm_min, &n) != 2) throw bad();
    at += 1 + size_t(n);
    if (at < text.size() && text[at] == ':') {
      if (std::sscanf(text.c_str() + at + 1, "%2d%n", &tm.tm_sec, &n) != 1) throw bad();
      at += 1 + size_t(n);
    }
  }
  long offset = 0;
  if (at < text.size() && text[at] == 'Z') {
    ++at;
  } else if (at < text.size() && (text[at] == '+' || text[at] == '-')) {
    int h = 0, m = 0, n = 0;
    if (std::sscanf(text.c_str() + at + 1, "%2d:%2d%n", &h, &m, &n) != 2) throw bad();
    offset = (text[at] == '+' ? 1 : -1) * (h * 3600L + m * 60L);
    at += 1 + size_t(n);
  }
  if (at != text.size() || tm.tm_mon < 1 || tm.tm_mon > 12 || tm.tm_mday < 1 || tm.tm_mday > 31 || tm.tm_hour > 23 ||
      tm.tm_min > 59 || tm.tm_sec > 60)
    throw bad();
  tm.tm_year -= 1900;
  tm.tm_mon -= 1;
  const long long seconds = timegm(&tm) - offset;
  if (seconds < kFirstPrintableSecond || seconds > kLastPrintableSecond)
    throw InputError("", std::nullopt, "--date", fmt::format("{} is outside 0001-01-01 .. 9999-12-31, the dates every export prints", text));
  return double(seconds);
}

}  // namespace aor::cli
