#include "options/progress.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <memory>

#include <fmt/format.h>

namespace aor {
namespace {

constexpr int kBarWidth = 30;

double steadySeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double lineSecondsFromEnvironment() {
  const char* text = std::getenv("AOREPLAY_PROGRESS_SECONDS");
  if (!text) return 5.0;
  char* end = nullptr;
  double seconds = std::strtod(text, &end);
  return end != text && seconds >= 0 ? seconds : 5.0;
}

std::string duration(double seconds) {
  if (seconds < 90) return fmt::format("{:.1f} s", seconds);
  if (seconds < 5400) return fmt::format("{:.1f} min", seconds / 60);
  return fmt::format("{:.1f} h", seconds / 3600);
}

}  // namespace

Progress::Progress(std::string label, std::string unit, int total, FILE* out)
    : Progress(std::move(label), std::move(unit), total, out, isatty(fileno(out)) != 0, lineSecondsFromEnvironment(), steadySeconds) {}

Progress::Progress(std::string label, std::string unit, int total, FILE* out, bool terminal, double lineSeconds, Clock clock)
    : label_(std::move(label)), unit_(std::move(unit)), total_(std::max(total, 1)), out_(out), terminal_(terminal),
      lineSeconds_(lineSeconds), clock_(std::move(clock)), start_(clock_()), lastLine_(start_) {}

std::string Progress::status(const std::string& unit, int done, int total, double elapsed) {
  std::string text = fmt::format("{}/{} {}, {}", done, total, unit, duration(elapsed));
  if (done >= total) return text + ", done";
  if (done <= 0) return text;
  return text + fmt::format(", about {} left", duration(elapsed / done * (total - done)));
}

void Progress::update(int done) {
  done = std::clamp(done, 0, total_);
  double now = clock_(), elapsed = now - start_;
  std::string text = status(unit_, done, total_, elapsed);
  if (terminal_) {
    int filled = done * kBarWidth / total_;
    fmt::print(out_, "\r{} [{}{}] {}\033[K{}", label_, std::string(size_t(filled), '#'), std::string(size_t(kBarWidth - filled), '-'),
               text, done == total_ ? "\n" : "");
  } else if (now - lastLine_ >= lineSeconds_ || (done == total_ && printedLine_)) {
    // Short work stays quiet off a terminal; long work gets a line every lineSeconds and the last.
    fmt::print(out_, "{}: {}\n", label_, text);
    lastLine_ = now;
    printedLine_ = true;
  }
  std::fflush(out_);
}

std::function<void(int, int)> progressCallback(std::string label, std::string unit) {
  auto progress = std::make_shared<std::unique_ptr<Progress>>();
  return [progress, label = std::move(label), unit = std::move(unit)](int done, int total) {
    if (!*progress) *progress = std::make_unique<Progress>(label, unit, total);
    (*progress)->update(done);
  };
}

}  // namespace aor
