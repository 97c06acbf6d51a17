// Progress lines and bars with a fake clock: what is done, the time so far and the time left.
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "options/progress.h"

namespace aor {
namespace {

std::string drain(FILE* f) {
  std::fflush(f);
  std::rewind(f);
  std::string text;
  for (int c; (c = std::fgetc(f)) != EOF;) text += char(c);
  return text;
}

TEST(Progress, StatusEstimatesTheTimeLeftFromThePaceSoFar) {
  EXPECT_EQ(Progress::status("frames", 0, 8, 0.0), "0/8 frames, 0.0 s");
  EXPECT_EQ(Progress::status("frames", 2, 8, 3.0), "2/8 frames, 3.0 s, about 9.0 s left");
  EXPECT_EQ(Progress::status("frames", 1, 100, 30.0), "1/100 frames, 30.0 s, about 49.5 min left");
  EXPECT_EQ(Progress::status("frames", 8, 8, 12.0), "8/8 frames, 12.0 s, done");
}

TEST(Progress, OffATerminalPrintsALineEveryFewSecondsAndTheLast) {
  FILE* out = std::tmpfile();
  double now = 100.0;
  Progress progress("capture", "frames", 4, out, false, 5.0, [&] { return now; });
  now = 102.0;
  progress.update(1);  // too soon for a line
  now = 106.0;
  progress.update(2);
  now = 108.0;
  progress.update(3);  // 2 s after the last line
  now = 112.0;
  progress.update(4);
  EXPECT_EQ(drain(out), "capture: 2/4 frames, 6.0 s, about 6.0 s left\ncapture: 4/4 frames, 12.0 s, done\n");
  std::fclose(out);
}

TEST(Progress, ShortWorkOffATerminalStaysQuiet) {
  FILE* out = std::tmpfile();
  double now = 0.0;
  Progress progress("replay", "frames", 2, out, false, 5.0, [&] { return now; });
  now = 0.5;
  progress.update(1);
  now = 1.0;
  progress.update(2);
  EXPECT_EQ(drain(out), "");
  std::fclose(out);
}

TEST(Progress, OnATerminalRedrawsABarInPlace) {
  FILE* out = std::tmpfile();
  double now = 0.0;
  Progress progress("sweep", "configurations", 2, out, true, 5.0, [&] { return now; });
  now = 1.0;
  progress.update(1);
  now = 2.0;
  progress.update(2);
  std::string text = drain(out);
  EXPECT_NE(text.find("\rsweep [###############---------------] 1/2 configurations, 1.0 s, about 1.0 s left"), std::string::npos) << text;
  EXPECT_NE(text.find("\rsweep [##############################] 2/2 configurations, 2.0 s, done\033[K\n"), std::string::npos) << text;
  std::fclose(out);
}

}  // namespace
}  // namespace aor
