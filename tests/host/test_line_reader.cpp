#include <gtest/gtest.h>

#include <string>

#include "core/line_reader.h"

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
