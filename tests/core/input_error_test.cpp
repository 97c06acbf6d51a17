#include "core/input_error.h"

#include <gtest/gtest.h>

namespace aor {
namespace {

TEST(InputError, MessageNamesFileFrameAndField) {
  const InputError e("captures/x/capture.json", 3, "view", "expected 16 numbers, got 15");
  EXPECT_STREQ(e.what(), "captures/x/capture.json: frame 3: field \"view\": expected 16 numbers, got 15");
  EXPECT_EQ(e.file, "captures/x/capture.json");
  ASSERT_TRUE(e.frame.has_value());
  EXPECT_EQ(*e.frame, 3);
  EXPECT_EQ(e.field, "view");
}

TEST(InputError, ExrFieldsAreChannels) {
  const InputError e("captures/x/frames/0002.exr", 2, "depth", "has type HALF, expected FLOAT");
  EXPECT_STREQ(e.what(), "captures/x/frames/0002.exr: frame 2: channel \"depth\": has type HALF, expected FLOAT");
}

TEST(InputError, OmitsUnknownParts) {
  EXPECT_STREQ(InputError("a/capture.json", std::nullopt, "", "malformed JSON").what(), "a/capture.json: malformed JSON");
  EXPECT_STREQ(InputError("a/capture.json", 0, "", "x").what(), "a/capture.json: frame 0: x");
  EXPECT_STREQ(InputError("", std::nullopt, "radius", "must be positive").what(), "setting \"radius\": must be positive");
}

TEST(InputError, MessageIsOneLine) {
  const InputError e("f.exr", std::nullopt, "", "line one\nline two\r\tend");
  EXPECT_STREQ(e.what(), "f.exr: line one line two  end");
}

// Issue 44: no control character reaches the terminal through a message, C1 (U+009B, a CSI in
// UTF-8 terminals) and escape included; other UTF-8 stays.
TEST(InputError, MessageMovesNoCursor) {
  InputError e("s.json", std::nullopt, "k\x1b[31m", "red \xc2\x9b" "31m, \xc2\xa0 \xc3\xa9");
  EXPECT_STREQ(e.what(), "s.json: field \"k [31m\": red   31m, \xc2\xa0 \xc3\xa9");
}

TEST(InputError, IsARuntimeError) {
  try {
    throw InputError("f", 1, "g", "h");
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "f: frame 1: field \"g\": h");
    return;
  }
  FAIL() << "not caught as std::runtime_error";
}

}  // namespace
}  // namespace aor
