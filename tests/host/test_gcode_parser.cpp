// core/text/gcode_parser.h: the grammar (words, blanks, case, comments, line
// numbers), codes and modal groups, the parser's errors and the checksum
// helper. The interpreter's errors are in test_gcode_errors.cpp.
#include <gtest/gtest.h>

#include <string>

#include "core/text/gcode_parser.h"

using am::GcodeBlock;
using am::GcodeCode;
using am::GcodeError;
using am::GcodeGroup;

namespace {

GcodeError parse(const char* line, GcodeBlock& b) { return am::parse_gcode(line, b); }
GcodeError parse(const char* line) {
  GcodeBlock b;
  return am::parse_gcode(line, b);
}

uint32_t bit(char c) { return uint32_t(1) << (c - 'A'); }

}  // namespace

TEST(GcodeParser, SlicerLine) {
  GcodeBlock b;
  ASSERT_EQ(parse("G1 X110.956 Y98.211 E2.0151", b), GcodeError::none);
  EXPECT_EQ(b.group(GcodeGroup::motion), GcodeCode::g1);
  EXPECT_EQ(b.words, bit('X') | bit('Y') | bit('E'));
  EXPECT_EQ(b.get('X'), 1109560);
  EXPECT_EQ(b.get('Y'), 982110);
  EXPECT_EQ(b.get('E'), 20151);
  for (GcodeGroup g : {GcodeGroup::plane, GcodeGroup::distance, GcodeGroup::units, GcodeGroup::feed_mode,
                       GcodeGroup::non_modal, GcodeGroup::stop, GcodeGroup::extruder, GcodeGroup::machine})
    EXPECT_EQ(b.group(g), GcodeCode::none);
}

TEST(GcodeParser, CaseBlanksAndNoSeparators) {
  GcodeBlock a, b, c;
  ASSERT_EQ(parse("g1x10y-2.5f300", a), GcodeError::none);
  ASSERT_EQ(parse("  G 1\tX 10   Y -2.5 F 300  ", b), GcodeError::none);
  ASSERT_EQ(parse("G01 X+10.000 Y-2.50 F300.", c), GcodeError::none);
  for (const GcodeBlock* p : {&a, &b, &c}) {
    EXPECT_EQ(p->group(GcodeGroup::motion), GcodeCode::g1);
    EXPECT_EQ(p->words, bit('X') | bit('Y') | bit('F'));
    EXPECT_EQ(p->get('X'), 100000);
    EXPECT_EQ(p->get('Y'), -25000);
    EXPECT_EQ(p->get('F'), 3000000);
  }
  // No blank after a sign.
  EXPECT_EQ(parse("G1 X- 10"), GcodeError::bad_number);
  // The number ends where a letter starts: "X1e5" is X1 and E5.
  ASSERT_EQ(parse("G1 X1e5", a), GcodeError::none);
  EXPECT_EQ(a.get('X'), 10000);
  EXPECT_EQ(a.get('E'), 50000);
}

TEST(GcodeParser, CommentsAndEmptyLines) {
  GcodeBlock b;
  for (const char* line : {"", "   ", "\t", "; only a comment", "(only a comment)", "(a) (b) ; c", "%", "  % "}) {
    ASSERT_EQ(parse(line, b), GcodeError::none) << line;
    EXPECT_EQ(b.words, 0u) << line;
    for (uint8_t g = 0; g < am::kGcodeGroups; ++g) EXPECT_EQ(b.code[g], GcodeCode::none) << line;
  }
  ASSERT_EQ(parse("G0 (move; fast) X5 (to five) ; Y7 is commented out", b), GcodeError::none);
  EXPECT_EQ(b.words, bit('X'));
  EXPECT_EQ(b.get('X'), 50000);
  ASSERT_EQ(parse("G1X1(c)Y2", b), GcodeError::none);
  EXPECT_EQ(b.words, bit('X') | bit('Y'));
  ASSERT_EQ(parse("G1 X1 ; (unclosed in a ; comment is fine", b), GcodeError::none);
  EXPECT_EQ(parse("G1 X1 (unclosed"), GcodeError::bad_comment);
  EXPECT_EQ(parse("G1 (a (nested) b) X1"), GcodeError::bad_comment);
  EXPECT_EQ(parse("% G1 X1"), GcodeError::bad_character);
  EXPECT_EQ(parse("G1 X1 %"), GcodeError::bad_character);
}

TEST(GcodeParser, LineNumbers) {
  GcodeBlock b;
  ASSERT_EQ(parse("N10 G1 X1", b), GcodeError::none);
  EXPECT_TRUE(b.has('N'));
  EXPECT_EQ(b.get('N'), 10);  // an integer, not 1/10000
  ASSERT_EQ(parse("(first) n2147483647", b), GcodeError::none);
  EXPECT_EQ(b.get('N'), 2147483647);
  EXPECT_EQ(parse("G1 N10 X1"), GcodeError::bad_line_number);
  EXPECT_EQ(parse("N1 N2"), GcodeError::bad_line_number);
  EXPECT_EQ(parse("N1.5 G1"), GcodeError::bad_line_number);
  EXPECT_EQ(parse("N-3 G0"), GcodeError::bad_line_number);
  EXPECT_EQ(parse("N2147483648"), GcodeError::out_of_range);
  EXPECT_EQ(parse("N"), GcodeError::bad_number);
}

TEST(GcodeParser, CodesAndTheirGroups) {
  struct Case {
    const char* text;
    GcodeGroup group;
    GcodeCode code;
  };
  const Case cases[] = {
      {"G0", GcodeGroup::motion, GcodeCode::g0},        {"G00", GcodeGroup::motion, GcodeCode::g0},
      {"G1", GcodeGroup::motion, GcodeCode::g1},        {"G2", GcodeGroup::motion, GcodeCode::g2},
      {"G3", GcodeGroup::motion, GcodeCode::g3},        {"G4", GcodeGroup::non_modal, GcodeCode::g4},
      {"G17", GcodeGroup::plane, GcodeCode::g17},       {"G18", GcodeGroup::plane, GcodeCode::g18},
      {"G19", GcodeGroup::plane, GcodeCode::g19},       {"G20", GcodeGroup::units, GcodeCode::g20},
      {"G21", GcodeGroup::units, GcodeCode::g21},       {"G90", GcodeGroup::distance, GcodeCode::g90},
      {"G91", GcodeGroup::distance, GcodeCode::g91},    {"G92", GcodeGroup::non_modal, GcodeCode::g92},
      {"G94", GcodeGroup::feed_mode, GcodeCode::g94},   {"M2", GcodeGroup::stop, GcodeCode::m2},
      {"M30", GcodeGroup::stop, GcodeCode::m30},        {"M82", GcodeGroup::extruder, GcodeCode::m82},
      {"M83", GcodeGroup::extruder, GcodeCode::m83},    {"M17", GcodeGroup::machine, GcodeCode::m17},
      {"M18", GcodeGroup::machine, GcodeCode::m18},     {"M84", GcodeGroup::machine, GcodeCode::m84},
      {"M114", GcodeGroup::machine, GcodeCode::m114},   {"m350", GcodeGroup::machine, GcodeCode::m350},
      {"M002", GcodeGroup::stop, GcodeCode::m2},
  };
  for (const Case& c : cases) {
    GcodeBlock b;
    ASSERT_EQ(parse(c.text, b), GcodeError::none) << c.text;
    for (uint8_t g = 0; g < am::kGcodeGroups; ++g)
      EXPECT_EQ(b.code[g], g == uint8_t(c.group) ? c.code : GcodeCode::none) << c.text;
    EXPECT_EQ(am::gcode_group(c.code), c.group) << c.text;
  }
  // One code of each group on one line is fine.
  GcodeBlock b;
  ASSERT_EQ(parse("G1 G17 G90 G21 G94 G4 M2 M82 M114", b), GcodeError::none);
  EXPECT_EQ(b.group(GcodeGroup::motion), GcodeCode::g1);
  EXPECT_EQ(b.group(GcodeGroup::plane), GcodeCode::g17);
  EXPECT_EQ(b.group(GcodeGroup::distance), GcodeCode::g90);
  EXPECT_EQ(b.group(GcodeGroup::units), GcodeCode::g21);
  EXPECT_EQ(b.group(GcodeGroup::feed_mode), GcodeCode::g94);
  EXPECT_EQ(b.group(GcodeGroup::non_modal), GcodeCode::g4);
  EXPECT_EQ(b.group(GcodeGroup::stop), GcodeCode::m2);
  EXPECT_EQ(b.group(GcodeGroup::extruder), GcodeCode::m82);
  EXPECT_EQ(b.group(GcodeGroup::machine), GcodeCode::m114);
}

TEST(GcodeParser, UnsupportedCodes) {
  for (const char* line : {"G30", "G5", "G38", "G80", "G93", "G95", "G1.0", "G1.5", "G92.1", "G-1", "M0", "M4",
                           "M110", "M117", "M202", "M222", "M998", "M350.5", "G214748"})
    EXPECT_EQ(parse(line), GcodeError::unsupported_code) << line;
  EXPECT_EQ(parse("G9999999999"), GcodeError::out_of_range);
  // A parser without the printer's codes (an image without them).
  for (const char* line : {"M3 S200", "M5", "M73 P1", "M201 X1", "M203 X1", "M204 S1", "M205 J1", "M220", "M221"}) {
    GcodeBlock b;
    EXPECT_EQ(am::parse_gcode<false>(line, b), GcodeError::unsupported_code) << line;
    EXPECT_EQ(am::parse_gcode<true>(line, b), GcodeError::none) << line;
  }
}

TEST(GcodeParser, ModalGroupConflicts) {
  for (const char* line : {"G0 G1 X1", "G1 G1 X1", "G2 G3 X1 I1", "G17 G18", "G90 G91", "G20 G21", "G4 P1 G92 X0", "G28 G92 X0",
                           "M2 M30", "M82 M83", "M17 M18", "M114 M84", "M350 X1 M17", "M999 M17"})
    EXPECT_EQ(parse(line), GcodeError::modal_group_conflict) << line;
}

TEST(GcodeParser, WordErrors) {
  EXPECT_EQ(parse("G1 X1 X2"), GcodeError::repeated_word);
  EXPECT_EQ(parse("G1 x1 X2"), GcodeError::repeated_word);
  EXPECT_EQ(parse("G1 F100 X1 F200"), GcodeError::repeated_word);
  for (const char* line : {"G1 X1 L100", "L2", "H1", "O100", "G1 V1", "G1 W1"})
    EXPECT_EQ(parse(line), GcodeError::unsupported_word) << line;
  for (const char* line : {"G1 X10 20", "#1=5", "$H", "G1 X1*71", "G1 X1 )", "G1 X1 /", "G1 ,X1", "1"})
    EXPECT_EQ(parse(line), GcodeError::bad_character) << line;
  for (const char* line : {"G1 X", "G1 X-", "G1 X.", "G1 X1.2.3", "G", "G1 Y1..", "G X1"})
    EXPECT_EQ(parse(line), GcodeError::bad_number) << line;
  EXPECT_EQ(parse("G1 X214748.3648"), GcodeError::out_of_range);
  EXPECT_EQ(parse("G1 X-300000"), GcodeError::out_of_range);
}

TEST(GcodeParser, FirstErrorFromTheLeftWins) {
  EXPECT_EQ(parse("G1 X1 X2 T1"), GcodeError::repeated_word);
  EXPECT_EQ(parse("G1 L1 X1 X2"), GcodeError::unsupported_word);
  EXPECT_EQ(parse("G30 G0 G1"), GcodeError::unsupported_code);
  EXPECT_EQ(parse("G0 G1 G30"), GcodeError::modal_group_conflict);
}

TEST(GcodeParser, EndPointerStopsTheParse) {
  const char* line = "G1 X5 Y7";
  GcodeBlock b;
  ASSERT_EQ(am::parse_gcode(line, b, line + 6), GcodeError::none);  // "G1 X5 "
  EXPECT_EQ(b.words, bit('X'));
  ASSERT_EQ(am::parse_gcode(line, b, line + 5), GcodeError::none);  // "G1 X5"
  EXPECT_EQ(b.get('X'), 50000);
}

namespace {
uint8_t xor_of(const std::string& s) {
  uint8_t x = 0;
  for (unsigned char c : s) x ^= c;
  return x;
}
}  // namespace

TEST(GcodeParser, MarlinChecksumLayersOnTop) {
  const std::string payload = "N42 G1 X10.5 Y-3 E0.25";
  const std::string line = payload + "*" + std::to_string(xor_of(payload));
  const char* end = nullptr;
  ASSERT_EQ(am::split_checksum(line.c_str(), end), am::Checksum::ok);
  EXPECT_EQ(end, line.c_str() + payload.size());
  GcodeBlock b;
  ASSERT_EQ(am::parse_gcode(line.c_str(), b, end), GcodeError::none);
  EXPECT_EQ(b.get('N'), 42);
  EXPECT_EQ(b.get('E'), 2500);

  const std::string wrong = payload + "*" + std::to_string((xor_of(payload) + 1) & 0xFF);
  EXPECT_EQ(am::split_checksum(wrong.c_str(), end), am::Checksum::mismatch);
  EXPECT_EQ(am::split_checksum((payload + "*256").c_str(), end), am::Checksum::malformed);
  EXPECT_EQ(am::split_checksum((payload + "*0012").c_str(), end), am::Checksum::malformed);
  const std::string trailing = payload + "*" + std::to_string(xor_of(payload)) + "  ";
  EXPECT_EQ(am::split_checksum(trailing.c_str(), end), am::Checksum::ok);
  // No checksum: end is the NUL, the line is parsed whole.
  EXPECT_EQ(am::split_checksum(payload.c_str(), end), am::Checksum::absent);
  EXPECT_EQ(end, payload.c_str() + payload.size());
  // A '*' not followed by digits only is no checksum (the parser rejects it).
  const char* odd = "G1 X1 (a*b)";
  EXPECT_EQ(am::split_checksum(odd, end), am::Checksum::absent);
  ASSERT_EQ(am::parse_gcode(odd, b, end), GcodeError::none);
  EXPECT_EQ(am::split_checksum("G1 X1*", end), am::Checksum::absent);
}

TEST(GcodeParser, EveryErrorHasItsOwnMessage) {
  const uint8_t count = uint8_t(GcodeError::mode_not_available) + 1;
  for (uint8_t i = 0; i < count; ++i) {
    const std::string a = am::gcode_error_message(GcodeError(i));
    EXPECT_FALSE(a.empty());
    EXPECT_NE(a, "?");
    for (uint8_t j = 0; j < i; ++j) EXPECT_NE(a, am::gcode_error_message(GcodeError(j))) << int(i) << " " << int(j);
  }
}
