// core/plain_text.h: which characters count as control characters (C0 with tab and newline,
// DEL, C1) and how they and broken UTF-8 are written for a terminal, XML or generated code.
#include <gtest/gtest.h>

#include "core/input_error.h"
#include "core/plain_text.h"

namespace aor::test {
namespace {

TEST(PlainText, ControlCharactersAreC0DelAndC1ButNotOtherUtf8) {
  EXPECT_EQ(controlCharacterIn("plain text, é and ✓"), std::nullopt);
  EXPECT_EQ(controlCharacterIn("tab\there"), "\\x09 at byte 3");
  EXPECT_EQ(controlCharacterIn("line\n"), "\\x0a at byte 4");
  EXPECT_EQ(controlCharacterIn("del\x7f"), "\\x7f at byte 3");
  EXPECT_EQ(controlCharacterIn("c1 \xc2\x85 next line"), "\\x85 at byte 3");
  EXPECT_EQ(controlCharacterIn("nbsp \xc2\xa0 is text"), std::nullopt);
  EXPECT_EQ(controlCharacterIn(std::string("nul\0", 4)), "\\x00 at byte 3");
}

TEST(PlainText, PrintableEscapesControlsAndBrokenUtf8AndKeepsLinesOnlyWhenAsked) {
  EXPECT_EQ(printable("red \x1b[31m"), "red \\x1b[31m");
  EXPECT_EQ(printable("a\nb\tc"), "a\\x0ab\\x09c");
  EXPECT_EQ(printable("a\nb\tc\x01", true), "a\nb\tc\\x01");
  EXPECT_EQ(printable("é\xff\xc3"), "é\\xff\\xc3");
  EXPECT_EQ(printable("\xc2\x85"), "\\xc2\\x85");
  EXPECT_EQ(printable("✓ ok"), "✓ ok");
}

TEST(PlainText, WithoutControlCharactersNamesTheFileAndField) {
  EXPECT_EQ(withoutControlCharacters("fine", "f.json", "name"), "fine");
  try {
    withoutControlCharacters("bad\x1b", "f.json", "passes[2].name");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file, "f.json");
    EXPECT_EQ(e.field, "passes[2].name");
    EXPECT_NE(std::string(e.what()).find("\"bad\\u001b\" holds a control character (\\x1b at byte 3)"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace aor::test
