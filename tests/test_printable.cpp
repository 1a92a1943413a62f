// Text printed on one line of a terminal (demos/printable.h): control
// characters and the invisible characters that reorder or break text are
// escaped; every other character, UTF-8 included, is kept.
#include <gtest/gtest.h>

#include "output/printable.h"

namespace {

using output::printable;

TEST(Printable, ControlCharactersBecomeCEscapes) {
  EXPECT_EQ(printable("two\nlines\t\r\x1b[31m\x7f"), "two\\nlines\\t\\r\\x1b[31m\\x7f");
}

TEST(Printable, BidiOverridesIsolatesMarksAndSeparatorsBecomeUnicodeEscapes) {
  EXPECT_EQ(printable("evil\u202Etxt.exe"), "evil\\u202etxt.exe");
  EXPECT_EQ(printable("\u202A\u202B\u202C\u202D"), "\\u202a\\u202b\\u202c\\u202d");
  EXPECT_EQ(printable("\u2066\u2067\u2068\u2069"), "\\u2066\\u2067\\u2068\\u2069");
  EXPECT_EQ(printable("\u200E\u200F\u061C"), "\\u200e\\u200f\\u061c");
  EXPECT_EQ(printable("a\u2028b\u2029c"), "a\\u2028b\\u2029c");
  EXPECT_EQ(printable("\xc2\x85\xc2\x9b"), "\\u0085\\u009b");  // C1: NEL and CSI
}

TEST(Printable, OtherUtf8AndCutSequencesAreKept) {
  EXPECT_EQ(printable("Gauß–Seidel, Δt ≥ 0, 粒子"), "Gauß–Seidel, Δt ≥ 0, 粒子");
  EXPECT_EQ(printable("cut \xe2\x80"), "cut \xe2\x80");
  EXPECT_EQ(printable("\xc2\xa0"), "\xc2\xa0");  // no-break space, visible as a space
}

}  // namespace
