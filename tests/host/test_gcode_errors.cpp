// One test per row of the error table in docs/gcode.md: a real line that
// triggers the error, and the interpreter's whole state (modes, feed,
// coordinates, offsets, machine steps) unchanged afterwards. A last test
// reads the table itself and runs every example it gives, so the document
// and the code cannot drift apart.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "core/text/gcode_interpreter.h"

using am::GcodeError;

namespace {

// The m32 board's axes: X Y Z E on step/dir drivers at 1000 steps/mm, U a
// ULN2003 motor (wave, two-phase and half step only).
const am::GcodeAxis kM32[] = {{'X', 0, 1000000},
                              {'Y', 0, 1000000},
                              {'Z', 0, 1000000},
                              {'E', 0, 1000000},
                              {'U', am::kModesUnipolar, 4096}};
using Interp = am::GcodeInterpreter<5>;
using NoArcs = am::GcodeInterpreter<5, false>;  // the Uno's (firmware/apps/cnc/gcode.cpp, board::kArcs)
using NoHeater = am::GcodeInterpreter<5, false, false>;  // a board without a heater (the Uno's)
using State = am::GcodeState<5>;

template <typename I>
GcodeError run(I& g, const std::string& line) {
  am::GcodeAction<5> a;
  return g.run(line.c_str(), a);
}


void expect_same(const State& before, const State& after, const std::string& line) {
  EXPECT_EQ(int(before.modal.motion), int(after.modal.motion)) << line;
  EXPECT_EQ(int(before.modal.plane), int(after.modal.plane)) << line;
  EXPECT_EQ(before.modal.incremental, after.modal.incremental) << line;
  EXPECT_EQ(before.modal.inches, after.modal.inches) << line;
  EXPECT_EQ(before.modal.e_relative, after.modal.e_relative) << line;
  EXPECT_EQ(before.modal.feed, after.modal.feed) << line;
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(before.axis[i].coord, after.axis[i].coord) << line << " axis " << i;
    EXPECT_EQ(before.axis[i].offset, after.axis[i].offset) << line << " axis " << i;
    EXPECT_EQ(before.axis[i].steps, after.axis[i].steps) << line << " axis " << i;
  }
}

// A row's example: its setup lines, then the failing line, which must give
// `e` and change nothing.
template <typename I>
void check_row(I&& g, const std::vector<std::string>& example, GcodeError e, const std::string& name) {
  for (size_t k = 0; k + 1 < example.size(); ++k) ASSERT_EQ(run(g, example[k]), GcodeError::none) << example[k];
  const State before = g.state();
  EXPECT_EQ(run(g, example.back()), e) << name << ": " << example.back();
  expect_same(before, g.state(), example.back());
}

// A state where nothing is at its power-up value that a bad line could
// reset: X10 Y20 Z3, E offset by G92, feed 1500, E relative, G1.
void warm_up(Interp& g) {
  for (const char* line : {"G21 G90 G17 G1 X10 Y20 Z3 E7 U1 F1500", "G92 E0.5", "M83"})
    ASSERT_EQ(run(g, line), GcodeError::none) << line;
}

void check(GcodeError expected, const std::string& line, bool warm = true) {
  Interp g(kM32);
  if (warm) warm_up(g);
  const State before = g.state();
  EXPECT_EQ(run(g, line), expected) << line << ": " << am::gcode_error_message(run(g, line));
  expect_same(before, g.state(), line);
  // The same machine still takes good lines afterwards.
  EXPECT_EQ(run(g, "G1 X11"), warm ? GcodeError::none : GcodeError::bad_feed);
}

}  // namespace

TEST(GcodeErrors, BadCharacter) {
  check(GcodeError::bad_character, "G1 X15 #5");
  check(GcodeError::bad_character, "G1 X15 20");
}
TEST(GcodeErrors, BadComment) {
  check(GcodeError::bad_comment, "G1 X15 (to fifteen");
  check(GcodeError::bad_comment, "G1 (a (b) c) X15");
}
TEST(GcodeErrors, UnsupportedWord) { check(GcodeError::unsupported_word, "G1 X15 L1000"); }
TEST(GcodeErrors, BadNumber) {
  check(GcodeError::bad_number, "G1 X1.2.3");
  check(GcodeError::bad_number, "G1 X");
}
TEST(GcodeErrors, OutOfRange) {
  check(GcodeError::out_of_range, "G1 X300000");
  check(GcodeError::out_of_range, "G4 P-1");
  check(GcodeError::out_of_range, "G20 F9000");    // 228600 mm/min
  check(GcodeError::out_of_range, "G20 G2 X10.5 Y20 R9000");
}
TEST(GcodeErrors, BadLineNumber) {
  check(GcodeError::bad_line_number, "G1 N10 X15");
  check(GcodeError::bad_line_number, "N1.5 G1 X15");
}
TEST(GcodeErrors, UnsupportedCode) {
  check(GcodeError::unsupported_code, "G30");
  check(GcodeError::unsupported_code, "M202 X100");
}
TEST(GcodeErrors, ModalGroupConflict) {
  check(GcodeError::modal_group_conflict, "G0 G1 X15");
  check(GcodeError::modal_group_conflict, "G90 G91 X15");
}
TEST(GcodeErrors, RepeatedWord) { check(GcodeError::repeated_word, "G1 X15 X16"); }
TEST(GcodeErrors, NoSuchAxis) {
  check(GcodeError::no_such_axis, "G1 A5");
  check(GcodeError::no_such_axis, "G92 B0");
}
TEST(GcodeErrors, AxisConflict) {
  check(GcodeError::axis_conflict, "G92 X0 G1");
  check(GcodeError::axis_conflict, "G0 M350 U2");
}
TEST(GcodeErrors, MultipleActions) {
  check(GcodeError::multiple_actions, "G4 P1 G1 X15");
  check(GcodeError::multiple_actions, "G1 X15 M2");
  check(GcodeError::multiple_actions, "M114 X15");
  check(GcodeError::multiple_actions, "G92 X0 M18");
}
TEST(GcodeErrors, MissingAxisWord) {
  check(GcodeError::missing_axis_word, "G92");
  check(GcodeError::missing_axis_word, "M350");
  check(GcodeError::missing_axis_word, "G2 I5");
}
TEST(GcodeErrors, MissingDwellTime) { check(GcodeError::missing_dwell_time, "G4"); }
TEST(GcodeErrors, MissingArcWords) {
  check(GcodeError::missing_arc_words, "G2 X20 Y20");
  check(GcodeError::missing_arc_words, "G3 X20 Y20 K5");  // K is not in the XY plane
}
TEST(GcodeErrors, ArcMixedForm) { check(GcodeError::arc_mixed_form, "G2 X20 Y20 R5 I5"); }
TEST(GcodeErrors, UnusedWord) {
  check(GcodeError::unused_word, "G1 X15 P2");
  check(GcodeError::unused_word, "G0 X15 I5");
  check(GcodeError::unused_word, "G2 X20 Y20 I5 K1");
  check(GcodeError::unused_word, "G17 R5");
}
TEST(GcodeErrors, BadFeed) {
  check(GcodeError::bad_feed, "G1 X15 F0");
  check(GcodeError::bad_feed, "F-5");
  check(GcodeError::bad_feed, "G1 X15", false);  // no F since power-up
  check(GcodeError::bad_feed, "G2 X20 Y20 I5 F0");
}
TEST(GcodeErrors, ArcZeroRadius) {
  check(GcodeError::arc_zero_radius, "G2 X10 Y20 I0 J0");
  check(GcodeError::arc_zero_radius, "G2 X15 R0");
}
TEST(GcodeErrors, ArcRadiusMismatch) { check(GcodeError::arc_radius_mismatch, "G2 X20 Y20 I4"); }
TEST(GcodeErrors, ArcRadiusTooSmall) { check(GcodeError::arc_radius_too_small, "G2 X20 Y20 R4"); }
TEST(GcodeErrors, ArcFullCircleR) { check(GcodeError::arc_full_circle_r, "G2 X10 Y20 R5"); }
TEST(GcodeErrors, TargetOutOfRange) {
  check(GcodeError::target_out_of_range, "G91 G0 X214748");  // from X10
  check(GcodeError::target_out_of_range, "G20 G0 X8455");    // 214757 mm
}
TEST(GcodeErrors, BadMode) {
  check(GcodeError::bad_mode, "M350 U4");
  check(GcodeError::bad_mode, "M350 U1.5");
}
TEST(GcodeErrors, AxisHasNoModes) { check(GcodeError::axis_has_no_modes, "M350 X16"); }
TEST(GcodeErrors, ModeNotAvailable) { check(GcodeError::mode_not_available, "M350 U16"); }
TEST(GcodeErrors, NoHeater) {
  for (const char* line : {"M104 S200", "M105", "M109 R100", "M155 S1", "M301 P1", "M303", "M108"}) {
    NoHeater g(kM32);
    EXPECT_EQ(run(g, line), GcodeError::no_heater) << line;
  }
}
TEST(GcodeErrors, HeaterCodeAlone) {
  check(GcodeError::heater_code_alone, "G90 M104 S200");
  check(GcodeError::heater_code_alone, "M105 G4 P1");
  check(GcodeError::modal_group_conflict, "M104 S200 M114");  // one machine code a line
}
TEST(GcodeErrors, HeaterWords) {
  check(GcodeError::unused_word, "M104 S200 X1");  // no move beside a heater code
  check(GcodeError::unused_word, "M105 S1");
  check(GcodeError::unused_word, "M109 S200 R190");
  check(GcodeError::unused_word, "M301 S1");
  check(GcodeError::missing_temperature, "M104");
  check(GcodeError::missing_temperature, "M109");
  check(GcodeError::missing_temperature, "M155");
}
TEST(GcodeErrors, BadTemperature) {
  check(GcodeError::bad_temperature, "M104 S-1");
  check(GcodeError::bad_temperature, "M104 S260.01");
  check(GcodeError::bad_temperature, "M109 R300");
  check(GcodeError::bad_temperature, "M303 S0");
}
TEST(GcodeErrors, BadInterval) {
  check(GcodeError::bad_interval, "M155 S61");
  check(GcodeError::bad_interval, "M155 S0.5");
  check(GcodeError::bad_interval, "M155 S-1");
}
TEST(GcodeErrors, BadGains) {
  check(GcodeError::bad_gains, "M301 P1000.1");
  check(GcodeError::bad_gains, "M301 I-1");
  check(GcodeError::bad_gains, "M301 P22.2 I1.08 D10001");
}
TEST(GcodeErrors, BadCycles) {
  check(GcodeError::bad_cycles, "M303 S200 C2");
  check(GcodeError::bad_cycles, "M303 C21");
  check(GcodeError::bad_cycles, "M303 C4.5");
}

// The part fan on a printer (a board with a heater): M106's duty 0 .. 255,
// 255 without S, M107 0; beyond the range, or a word it does not take, an
// error; on a board without a heater neither code is in the image.
TEST(GcodeHeaterCodes, TheFan) {
  Interp g(kM32);
  am::GcodeAction<5> a;
  const struct {
    const char* line;
    am::GcodeCode code;
    uint8_t duty;
  } cases[] = {{"M106 S128", am::GcodeCode::m106, 128}, {"M106", am::GcodeCode::m106, 255},
               {"M106 S0", am::GcodeCode::m106, 0},     {"M106 S255", am::GcodeCode::m106, 255},
               {"M107", am::GcodeCode::m107, 0}};
  for (const auto& c : cases) {
    ASSERT_EQ(g.run(c.line, a), GcodeError::none) << c.line;
    EXPECT_EQ(a.kind, am::GcodeActionKind::heater) << c.line;
    EXPECT_EQ(a.heater.code, c.code) << c.line;
    EXPECT_EQ(a.heater.count, c.duty) << c.line;
  }
  for (const char* bad : {"M106 S256", "M106 S-1", "M106 S12.5"}) EXPECT_EQ(g.run(bad, a), GcodeError::out_of_range) << bad;
  EXPECT_EQ(g.run("M107 S10", a), GcodeError::unused_word);
  EXPECT_EQ(g.run("M106 P1 S10", a), GcodeError::unused_word);
  EXPECT_EQ(g.run("M106 G90", a), GcodeError::heater_code_alone);
  am::GcodeInterpreter<5, false, false> no_heater(kM32);
  EXPECT_EQ(no_heater.run("M106 S10", a), GcodeError::unsupported_code);
  EXPECT_EQ(no_heater.run("M107", a), GcodeError::unsupported_code);
}

// What the accepted heater codes carry.
TEST(GcodeHeaterCodes, Values) {
  Interp g(kM32);
  am::GcodeAction<5> a;
  ASSERT_EQ(g.run("M104 S215.5", a), GcodeError::none);
  EXPECT_EQ(a.kind, am::GcodeActionKind::heater);
  EXPECT_EQ(a.heater.code, am::GcodeCode::m104);
  EXPECT_EQ(a.heater.target, 21550);
  ASSERT_EQ(g.run("M104 S0", a), GcodeError::none);
  EXPECT_EQ(a.heater.target, 0);
  ASSERT_EQ(g.run("M104 S260", a), GcodeError::none);
  EXPECT_EQ(a.heater.target, 26000);
  ASSERT_EQ(g.run("M109 R180.004", a), GcodeError::none);
  EXPECT_EQ(a.heater.code, am::GcodeCode::m109);
  EXPECT_TRUE(a.heater.wait_cooling);
  EXPECT_EQ(a.heater.target, 18000);
  ASSERT_EQ(g.run("N5 M109 S200", a), GcodeError::none);
  EXPECT_FALSE(a.heater.wait_cooling);
  ASSERT_EQ(g.run("M155 S60", a), GcodeError::none);
  EXPECT_EQ(a.heater.count, 60);
  ASSERT_EQ(g.run("M301 P22.2 D114", a), GcodeError::none);
  EXPECT_EQ(a.heater.gains_given, 5);
  EXPECT_EQ(a.heater.gains[0], 22200u);
  EXPECT_EQ(a.heater.gains[2], 114000u);
  ASSERT_EQ(g.run("M301", a), GcodeError::none);
  EXPECT_EQ(a.heater.gains_given, 0);
  ASSERT_EQ(g.run("M303", a), GcodeError::none);
  EXPECT_EQ(a.heater.target, 15000);
  EXPECT_EQ(a.heater.count, 5);
  ASSERT_EQ(g.run("M303 S210 C8", a), GcodeError::none);  // C is the cycle count, not an axis
  EXPECT_EQ(a.heater.target, 21000);
  EXPECT_EQ(a.heater.count, 8);
  ASSERT_EQ(g.run("m105", a), GcodeError::none);
  EXPECT_EQ(a.heater.code, am::GcodeCode::m105);
  ASSERT_EQ(g.run("M108", a), GcodeError::none);
  EXPECT_EQ(a.heater.code, am::GcodeCode::m108);
}

// A line with an error after a valid part changes nothing either: the modal
// codes and F at its start are not applied.
TEST(GcodeErrors, NothingOfARefusedLineIsApplied) {
  check(GcodeError::bad_feed, "G20 G91 G18 M82 F0 G1 X1");
  check(GcodeError::arc_radius_mismatch, "G20 F10 G3 X1 I0.1");
  check(GcodeError::target_out_of_range, "G91 G0 X1 Y2 Z3 E4 U214748");  // U fails last
}

// The table in docs/gcode.md: every row's example, run from power-up on the
// m32 axes, gives that row's error and message.
TEST(GcodeErrors, DocumentedTableMatchesTheCode) {
  std::map<std::string, GcodeError> by_name;
#define NAME_OF(name, text) by_name[#name] = GcodeError::name;
  AM_GCODE_ERRORS(NAME_OF)
#undef NAME_OF
  std::string path = __FILE__;
  path = path.substr(0, path.rfind('/') + 1) + "../../docs/gcode.md";
  std::ifstream doc(path);
  ASSERT_TRUE(doc) << "cannot read " << path;
  std::string line;
  bool in_table = false;
  std::map<std::string, int> rows;
  while (std::getline(doc, line)) {
    if (line.rfind("## ", 0) == 0) in_table = line.find("Error table") != std::string::npos;
    if (!in_table || line.rfind("| `", 0) != 0) continue;
    // | `name` | `message` | `setup` ... `failing line` | note |
    std::vector<std::string> cells;
    std::stringstream ss(line.substr(1));
    std::string cell;
    while (std::getline(ss, cell, '|')) cells.push_back(cell);
    ASSERT_GE(cells.size(), 3u) << line;
    auto spans = [](const std::string& c) {
      std::vector<std::string> out;
      for (size_t a = c.find('`'); a != std::string::npos; a = c.find('`', a + 1)) {
        const size_t b = c.find('`', a + 1);
        if (b == std::string::npos) break;
        out.push_back(c.substr(a + 1, b - a - 1));
        a = b;
      }
      return out;
    };
    const std::vector<std::string> name = spans(cells[0]), message = spans(cells[1]), example = spans(cells[2]);
    ASSERT_EQ(name.size(), 1u) << line;
    ASSERT_EQ(message.size(), 1u) << line;
    ASSERT_GE(example.size(), 1u) << line;
    ASSERT_TRUE(by_name.count(name[0])) << name[0];
    const GcodeError e = by_name[name[0]];
    EXPECT_EQ(message[0], am::gcode_error_message(e)) << name[0];
    if (e == GcodeError::arcs_not_here) check_row(NoArcs(kM32), example, e, name[0]);
    else if (e == GcodeError::no_heater) check_row(NoHeater(kM32), example, e, name[0]);
    else check_row(Interp(kM32), example, e, name[0]);
    ++rows[name[0]];
  }
  // Every error but none has its row.
  for (const auto& kv : by_name) {
    if (kv.second != GcodeError::none) {
      EXPECT_EQ(rows[kv.first], 1) << kv.first << " rows in docs/gcode.md";
    }
  }
}
