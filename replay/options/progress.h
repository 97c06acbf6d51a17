#pragma once
// Progress of long work (capture with references, sweep, long replays) on standard error: on a
// terminal a bar redrawn in place; off one (CI logs, pipes) a line every few seconds, so a long
// job is never silent. Both say how much is done and estimate the time left from the pace so far.
#include <cstdio>
#include <functional>
#include <string>

namespace aor {

class Progress {
 public:
  using Clock = std::function<double()>;  // seconds, monotonic
  // `unit`: what is counted ("frames", "configurations"). Off a terminal a line is printed once
  // `lineSeconds` have passed since the last (or the start), and a last one when the work ends
  // after any (AOREPLAY_PROGRESS_SECONDS overrides the default of 5; 0 prints every step).
  Progress(std::string label, std::string unit, int total, FILE* out = stderr);
  Progress(std::string label, std::string unit, int total, FILE* out, bool terminal, double lineSeconds, Clock clock);
  void update(int done);  // done in [0, total]; the last update ends the bar's line

  // "1/8 frames, 2.0 s, about 14.0 s left" (no estimate before the first step is done).
  static std::string status(const std::string& unit, int done, int total, double elapsedSeconds);

 private:
  std::string label_, unit_;
  int total_;
  FILE* out_;
  bool terminal_;
  double lineSeconds_;
  Clock clock_;
  double start_ = 0, lastLine_ = 0;
  bool printedLine_ = false;
};

// A `progress(done, total)` callback (replayer, generator) that makes its Progress on the first call.
std::function<void(int done, int total)> progressCallback(std::string label, std::string unit);

}  // namespace aor
