#include <gtest/gtest.h>

#include <string>

#include "core/text/command_parser.h"

using am::Command;
using am::CommandKind;
using am::ParseError;

namespace {
ParseError parse(const char* line, Command& c) { return am::parse_command(line, c); }
ParseError parse(const char* line) {
  Command c;
  return am::parse_command(line, c);
}
}  // namespace

TEST(CommandParser, MoveWithAllWords) {
  Command c;
  ASSERT_EQ(parse("MOVE X-400 F800 A1600", c), ParseError::none);
  EXPECT_EQ(c.kind, CommandKind::move);
  EXPECT_EQ(c.axis, 'X');
  EXPECT_EQ(c.steps, -400);
  EXPECT_EQ(c.rate, 800u);
  EXPECT_EQ(c.accel, 1600u);
  EXPECT_EQ(c.given, am::kGivenRate | am::kGivenAccel);
  // One acceleration for both ramps: D is no word of MOVE.
  EXPECT_EQ(parse("MOVE X-400 F800 A1600 D3200", c), ParseError::unexpected_word);
}

TEST(CommandParser, CaseAndBlanksDoNotMatter) {
  Command c;
  ASSERT_EQ(parse("  move\ty25   f10 ", c), ParseError::none);
  EXPECT_EQ(c.axis, 'Y');
  EXPECT_EQ(c.steps, 25);
  EXPECT_EQ(c.given, am::kGivenRate);
}

TEST(CommandParser, OtherCommands) {
  Command c;
  ASSERT_EQ(parse("POS", c), ParseError::none);
  EXPECT_EQ(c.kind, CommandKind::position);
  ASSERT_EQ(parse("release", c), ParseError::none);
  EXPECT_EQ(c.kind, CommandKind::release);
  ASSERT_EQ(parse("WAIT", c), ParseError::none);
  EXPECT_EQ(c.kind, CommandKind::wait);
  EXPECT_EQ(parse("WAIT X1"), ParseError::unexpected_word);
}

TEST(CommandParser, MalformedLinesAreNamed) {
  EXPECT_EQ(parse(""), ParseError::empty);
  EXPECT_EQ(parse("   "), ParseError::empty);
  EXPECT_EQ(parse("MOVEX10"), ParseError::unknown_command);
  EXPECT_EQ(parse("JUMP X10"), ParseError::unknown_command);
  EXPECT_EQ(parse("MOVE"), ParseError::missing_axis);
  EXPECT_EQ(parse("MOVE F100"), ParseError::missing_axis);
  EXPECT_EQ(parse("MOVE X"), ParseError::bad_number);
  EXPECT_EQ(parse("MOVE X1.5"), ParseError::bad_number);
  EXPECT_EQ(parse("MOVE X--1"), ParseError::bad_number);
  EXPECT_EQ(parse("MOVE 10"), ParseError::bad_word);
  EXPECT_EQ(parse("MOVE X10 X20"), ParseError::duplicate_word);
  EXPECT_EQ(parse("MOVE X10 Y20 X3"), ParseError::duplicate_word);
  EXPECT_EQ(parse("MOVE X10 F1 F2"), ParseError::duplicate_word);
  EXPECT_EQ(parse("MOVE X10 Q5"), ParseError::unexpected_word);
  EXPECT_EQ(parse("MOVE X10 F-5"), ParseError::out_of_range);
}

TEST(CommandParser, NumbersAreRangeChecked) {
  Command c;
  ASSERT_EQ(parse("MOVE X2147483647", c), ParseError::none);
  EXPECT_EQ(c.steps, 2147483647);
  ASSERT_EQ(parse("MOVE X-2147483647", c), ParseError::none);
  EXPECT_EQ(c.steps, -2147483647);
  EXPECT_EQ(parse("MOVE X2147483648"), ParseError::out_of_range);
  EXPECT_EQ(parse("MOVE X99999999999999999999"), ParseError::out_of_range);
}

TEST(CommandParser, ModeTakesOneAxisAndAModeNumber) {
  Command c;
  const int32_t modes[] = {0, 1, 2, 16, 32, 64};
  for (int32_t m : modes) {
    const std::string line = "MODE X" + std::to_string(m);
    ASSERT_EQ(parse(line.c_str(), c), ParseError::none) << line;
    EXPECT_EQ(c.kind, CommandKind::mode);
    EXPECT_EQ(c.axis, 'X');
    EXPECT_EQ(c.steps, m);
  }
  ASSERT_EQ(parse("mode y16", c), ParseError::none);
  EXPECT_EQ(c.axis, 'Y');
  EXPECT_EQ(parse("MODE X3"), ParseError::bad_mode);
  EXPECT_EQ(parse("MODE X8"), ParseError::bad_mode);
  EXPECT_EQ(parse("MODE X128"), ParseError::bad_mode);
  EXPECT_EQ(parse("MODE X-1"), ParseError::bad_mode);
  EXPECT_EQ(parse("MODE"), ParseError::missing_axis);
  EXPECT_EQ(parse("MODE X16 Y16"), ParseError::two_axes);
  EXPECT_EQ(parse("MODE X16 F100"), ParseError::unexpected_word);
  EXPECT_EQ(parse("MODEX16"), ParseError::unknown_command);
}

TEST(CommandParser, MoveTakesEveryAxisOnceInLineOrder) {
  Command c;
  ASSERT_EQ(parse("MOVE Y-3 X10 U7 E0 Z2147483647 F9", c), ParseError::none);
  ASSERT_EQ(c.axis_count, 5u);
  const char letters[] = {'Y', 'X', 'U', 'E', 'Z'};
  const int32_t steps[] = {-3, 10, 7, 0, 2147483647};
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(c.axes[i], letters[i]);
    EXPECT_EQ(c.axis_steps[i], steps[i]);
  }
  EXPECT_EQ(c.axis, 'Y');
  EXPECT_EQ(c.steps, -3);
  EXPECT_EQ(parse("MOVE X1 x2"), ParseError::duplicate_word);
}
