#include <gtest/gtest.h>

#include <string>

#include "core/text/line_reader.h"

namespace {
using Reader = am::LineReader<8>;

Reader::Line feed(Reader& r, const std::string& s) {
  Reader::Line last = Reader::Line::none;
  for (char c : s) last = r.feed(c);
  return last;
}
}  // namespace

TEST(LineReader, EveryLineEndingEndsALine) {
  Reader r;
  EXPECT_EQ(feed(r, "ab\n"), Reader::Line::ready);
  EXPECT_STREQ(r.text(), "ab");
  EXPECT_EQ(feed(r, "cd\r"), Reader::Line::ready);
  EXPECT_STREQ(r.text(), "cd");
  EXPECT_EQ(feed(r, "\n"), Reader::Line::none);  // the LF of a CRLF
  EXPECT_EQ(feed(r, "ef\r\n"), Reader::Line::none);
  EXPECT_STREQ(r.text(), "ef");
}

TEST(LineReader, FullCapacityFitsAndOneMoreDoesNot) {
  Reader r;
  EXPECT_EQ(feed(r, "12345678\n"), Reader::Line::ready);
  EXPECT_STREQ(r.text(), "12345678");
  EXPECT_EQ(feed(r, "123456789\n"), Reader::Line::too_long);
  // The next line is whole again.
  EXPECT_EQ(feed(r, "ok\n"), Reader::Line::ready);
  EXPECT_STREQ(r.text(), "ok");
}

TEST(LineReader, EmptyLinesAreSkipped) {
  Reader r;
  EXPECT_EQ(feed(r, "\n\n\r\n"), Reader::Line::none);
}

TEST(LineReader, EveryByteOutsidePrintableAsciiRefusesTheWholeLine) {
  // Every byte value at the start, in the middle and at the end of a line:
  // printable ASCII and TAB make a line, anything else refuses it whole.
  for (int b = 0; b < 256; ++b) {
    if (b == '\n' || b == '\r') continue;
    const bool allowed = (b >= 0x20 && b < 0x7F) || b == '\t';
    for (const std::string& line : {std::string(1, char(b)) + "ab", "a" + std::string(1, char(b)) + "b",
                                    "ab" + std::string(1, char(b))}) {
      Reader r;
      EXPECT_EQ(feed(r, line + "\n"), allowed ? Reader::Line::ready : Reader::Line::bad_byte) << "byte " << b;
      if (allowed) {
        EXPECT_EQ(std::string(r.text()), line);
      }
      // The line after it is whole again.
      EXPECT_EQ(feed(r, "ok\n"), Reader::Line::ready);
      EXPECT_STREQ(r.text(), "ok");
    }
  }
}

TEST(LineReader, AnOverlongLineWithABadByteIsTooLong) {
  Reader r;
  EXPECT_EQ(feed(r, std::string("1234") + '\0' + "56789\n"), Reader::Line::too_long);
  EXPECT_EQ(feed(r, std::string("12") + '\0' + "\n"), Reader::Line::bad_byte);
}
