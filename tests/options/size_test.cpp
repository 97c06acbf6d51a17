// parseSize ("WxH"), used by `aoreplay capture --size` and ao_bench's --sizes and --scaling-size.
#include "options/size.h"

#include <cstdio>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/input_error.h"

namespace aor {
namespace {

using Size = std::pair<int, int>;

TEST(ParseSize, AcceptsWidthXHeight) {
  EXPECT_EQ(parseSize("640x360", "--size"), Size(640, 360));
  EXPECT_EQ(parseSize("1x1", "--size"), Size(1, 1));
  EXPECT_EQ(parseSize("3840x2160", "--size"), Size(3840, 2160));
  EXPECT_EQ(parseSize("2147483647x2147483647", "--size"), Size(2147483647, 2147483647));
}

TEST(ParseSize, RejectsJunk) {
  for (const char* text : {"640x360x9", "640x", "x360", "0x10", "10x0", "-1x5", "5x-1", "640X360", "640 x360",
                           "640x360 ", "640x360\n", "640", "", "x", "640*360", "1.5x2", "0x0", "640x360,",
                           "2147483648x1", "1x99999999999", "99999999999x10"}) {
    EXPECT_THROW(parseSize(text, "--size"), InputError) << '"' << text << '"';
  }
}

TEST(ParseSize, MessageNamesTheFlagAndTheValue) {
  try {
    parseSize("640x", "--sizes");
    FAIL() << "640x accepted";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "setting \"--sizes\": '640x' is not WxH with positive sizes");
    EXPECT_EQ(e.field, "--sizes");
  }
}

// `aoreplay capture --size` parsed with this before parseSize existed; its accepted set is kept.
std::optional<Size> capturesOldRule(const std::string& text) {
  int w = 0, h = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || x != 'x' || w <= 0 || h <= 0)
    return std::nullopt;
  return Size(w, h);
}

// Every string of up to 6 characters over digits, x, X, space, tab, + and - (too short to overflow
// an int, where sscanf's result is undefined): accepted exactly when the old rule accepted it, with
// the same numbers. This keeps e.g. " 640x 360" and "+640x+360", which the old rule took.
TEST(ParseSize, AcceptsExactlyWhatTheCaptureCommandAcceptedBefore) {
  const std::string alphabet = "017xX \t+-";
  std::vector<std::string> level{""};
  int accepted = 0, checked = 0;
  for (int length = 1; length <= 6; ++length) {
    std::vector<std::string> next;
    for (const auto& prefix : level)
      for (char c : alphabet) next.push_back(prefix + c);
    for (const auto& text : next) {
      std::optional<Size> mine;
      try {
        mine = parseSize(text, "--size");
      } catch (const InputError&) {
      }
      ASSERT_EQ(mine, capturesOldRule(text)) << '"' << text << '"';
      accepted += mine.has_value();
      ++checked;
    }
    level = std::move(next);
  }
  EXPECT_GT(accepted, 1000) << "of " << checked;
  EXPECT_EQ(capturesOldRule(" 640x 360"), Size(640, 360));
  EXPECT_EQ(parseSize(" 640x 360", "--size"), Size(640, 360));
  EXPECT_EQ(parseSize("+640x+360", "--size"), Size(640, 360));
}

}  // namespace
}  // namespace aor
