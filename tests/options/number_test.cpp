// parseInt / parseNumber, used by ao_bench's --reps, --warmup, --warmup-ms and --extra-slices.
#include "options/number.h"

#include <gtest/gtest.h>

#include "core/input_error.h"

namespace aor {
namespace {

TEST(ParseInt, AcceptsWholeNumbersInRange) {
  EXPECT_EQ(parseInt("5", "--reps", 5, 100000), 5);
  EXPECT_EQ(parseInt("100000", "--reps", 5, 100000), 100000);
  EXPECT_EQ(parseInt("0", "--warmup", 0, 10), 0);
  EXPECT_EQ(parseInt("-3", "--x", -5, 5), -3);
}

TEST(ParseInt, RejectsJunkAndOutOfRangeNamingTheOption) {
  for (const char* text : {"", "abc", "12abc", " 12", "12 ", "+12", "1.5", "1e3", "4", "100001", "99999999999", "0x10"}) {
    try {
      parseInt(text, "--reps", 5, 100000);
      ADD_FAILURE() << '"' << text << "\" accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.field, "--reps");
      EXPECT_NE(std::string(e.what()).find(std::string("'") + text + "'"), std::string::npos) << e.what();
    }
  }
}

TEST(ParseNumber, AcceptsDecimalsInRangeAndRejectsTheRest) {
  EXPECT_EQ(parseNumber("300", "--warmup-ms", 0, 1e6), 300.0);
  EXPECT_EQ(parseNumber("0.5", "--warmup-ms", 0, 1e6), 0.5);
  EXPECT_EQ(parseNumber("1e3", "--warmup-ms", 0, 1e6), 1000.0);
  for (const char* text : {"", "abc", "1ms", "-1", "nan", "inf", "1e7", " 1"})
    EXPECT_THROW(parseNumber(text, "--warmup-ms", 0, 1e6), InputError) << '"' << text << '"';
}

}  // namespace
}  // namespace aor
