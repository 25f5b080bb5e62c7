// core/text/gcode_interpreter.h: feed, dwell, the M-functions, program end
// (modes restored, positions kept), the axis set as a parameter, the
// position range, unnamed axes and reset. Modes, units, distance modes and
// the double model: test_gcode_interpreter.cpp; the printer:
// gcode_printer.h.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/text/gcode_interpreter.h"
#include "gcode_printer.h"

using am::GcodeActionKind;
using am::GcodeError;
using gcodetest::Action;
using gcodetest::kPrinter;
using gcodetest::ok;
using gcodetest::Printer;
using gcodetest::run;

TEST(GcodeInterpreter, FeedRules) {
  Printer g(kPrinter);
  Action a;
  EXPECT_EQ(run(g, "G1 X1", a), GcodeError::bad_feed);  // no F yet
  a = ok(g, "G0 X1");  // a rapid needs none
  EXPECT_TRUE(a.rapid);
  a = ok(g, "G0 X2 F0");  // F0 may be set...
  EXPECT_EQ(g.state().modal.feed, 0);
  EXPECT_EQ(run(g, "G1 X3", a), GcodeError::bad_feed);  // ...but not fed with
  a = ok(g, "G1 X3 F0.5");
  EXPECT_FALSE(a.rapid);
  EXPECT_EQ(a.feed, 5000);
  a = ok(g, "X4");  // modal
  EXPECT_EQ(a.feed, 5000);
  EXPECT_EQ(a.kind, GcodeActionKind::move);
}

TEST(GcodeInterpreter, Dwell) {
  Printer g(kPrinter);
  Action a = ok(g, "G4 P1.5");
  EXPECT_EQ(a.kind, GcodeActionKind::dwell);
  EXPECT_EQ(a.dwell_ms, 1500u);
  a = ok(g, "G4 P0.0005");  // 0.5 ms rounds up
  EXPECT_EQ(a.dwell_ms, 1u);
  a = ok(g, "G4 P0.0004");
  EXPECT_EQ(a.dwell_ms, 0u);
  a = ok(g, "G4 P214748.3647");
  EXPECT_EQ(a.dwell_ms, 214748365u);
  a = ok(g, "G4 P0");
  EXPECT_EQ(a.dwell_ms, 0u);
}

// Marlin's G4 (the printer's dialect, GcodeInterpreter<..., true>): P in
// milliseconds, S in seconds, S winning over P; no word at all is still
// missing_dwell_time, and an unused word is still unused_word.
TEST(GcodeInterpreter, MarlinDwellTakesMillisecondsOrSeconds) {
  const am::GcodeAxis axes[] = {{'X', 0, 1000000}, {'Y', 0, 1000000}, {'Z', 0, 1000000}, {'E', 0, 1000000}};
  am::GcodeInterpreter<4, false, true, true> g(axes);
  am::GcodeAction<4> a;
  const struct {
    const char* line;
    uint32_t ms;
  } cases[] = {{"G4 P500", 500},         {"G4 P0.5", 1},       {"G4 P0.4999", 0},    {"G4 P214748.3647", 214748},
               {"G4 S2", 2000},          {"G4 S0.0005", 1},    {"G4 S0", 0},         {"G4 P500 S1.5", 1500},
               {"G4 S214748.3647", 214748365}};
  for (const auto& c : cases) {
    ASSERT_EQ(g.run(c.line, a), GcodeError::none) << c.line;
    EXPECT_EQ(a.kind, GcodeActionKind::dwell) << c.line;
    EXPECT_EQ(a.dwell_ms, c.ms) << c.line;
  }
  EXPECT_EQ(g.run("G4", a), GcodeError::missing_dwell_time);
  EXPECT_EQ(g.run("G4 P-1", a), GcodeError::out_of_range);
  EXPECT_EQ(g.run("G4 S-1", a), GcodeError::out_of_range);
  EXPECT_EQ(g.run("G4 P1 R2", a), GcodeError::unused_word);
  // The NGC/grbl reading keeps S out of G4.
  am::GcodeInterpreter<4, false, true> ngc(axes);
  EXPECT_EQ(ngc.run("G4 S2", a), GcodeError::missing_dwell_time);
  EXPECT_EQ(ngc.run("G4 P1 S2", a), GcodeError::unused_word);
}

TEST(GcodeInterpreter, MachineFunctions) {
  const am::GcodeAxis shield[] = {{'X', am::kModesShield, 1600000},
                                  {'Y', am::kModesShield, 1600000},
                                  {'U', am::kModesUnipolar, 262144},
                                  {'Z', 0, 400000}};
  am::GcodeInterpreter<4> g(shield);
  am::GcodeAction<4> a;
  ASSERT_EQ(g.run("M17", a), GcodeError::none);
  EXPECT_EQ(a.kind, GcodeActionKind::enable);
  ASSERT_EQ(g.run("M18", a), GcodeError::none);
  EXPECT_EQ(a.kind, GcodeActionKind::release);
  ASSERT_EQ(g.run("M84", a), GcodeError::none);
  EXPECT_EQ(a.kind, GcodeActionKind::release);
  ASSERT_EQ(g.run("G0 X1 Z2", a), GcodeError::none);
  ASSERT_EQ(g.run("M114", a), GcodeError::none);
  EXPECT_EQ(a.kind, GcodeActionKind::report_position);
  EXPECT_EQ(a.coord[0], 10000);
  EXPECT_EQ(a.target[0], 1600);
  EXPECT_EQ(a.target[3], 800);
  const struct {
    const char* line;
    uint8_t axes;
    uint8_t mode[3];
  } modes[] = {{"M350 X0", 1, {0}},         {"M350 X1 Y2", 3, {1, 2}},  {"M350 Y16", 2, {0, 16}},
               {"M350 X32 Y64 U2", 7, {32, 64, 2}}, {"M350 U0", 4, {0, 0, 0}}, {"M350 U1.0", 4, {0, 0, 1}}};
  for (const auto& m : modes) {
    ASSERT_EQ(g.run(m.line, a), GcodeError::none) << m.line;
    EXPECT_EQ(a.kind, GcodeActionKind::set_mode);
    EXPECT_EQ(a.axes, m.axes) << m.line;
    for (int i = 0; i < 3; ++i) {
      if (m.axes & (1 << i)) {
        EXPECT_EQ(a.mode[i], m.mode[i]) << m.line << " axis " << i;
      }
    }
    EXPECT_EQ(a.target[0], 1600);  // nothing moves
  }
  EXPECT_EQ(g.run("M350 Z16", a), GcodeError::axis_has_no_modes);
  EXPECT_EQ(g.run("M350 U32", a), GcodeError::mode_not_available);
  EXPECT_EQ(g.run("M350 X8", a), GcodeError::bad_mode);
  EXPECT_EQ(g.run("M350 X-1", a), GcodeError::bad_mode);
  EXPECT_EQ(g.run("M350 E16", a), GcodeError::no_such_axis);
  EXPECT_EQ(g.run("M17 X1", a), GcodeError::multiple_actions);
}

TEST(GcodeInterpreter, ProgramEndRestoresModesKeepsPositions) {
  Printer g(kPrinter);
  ok(g, "G20 G91 G18 M83 G1 X1 F10");
  ok(g, "G92 E5");
  const auto before = g.state();
  for (const char* end : {"M2", "M30"}) {
    const Action a = ok(g, end);
    EXPECT_EQ(a.kind, GcodeActionKind::program_end);
    const auto& s = g.state();
    EXPECT_EQ(s.modal.motion, am::Motion::rapid);
    EXPECT_EQ(s.modal.plane, am::Plane::xy);
    EXPECT_FALSE(s.modal.incremental);
    EXPECT_FALSE(s.modal.e_relative);
    EXPECT_TRUE(s.modal.inches);                     // kept
    EXPECT_EQ(s.modal.feed, before.modal.feed);      // kept
    for (int i = 0; i < 4; ++i) {
      EXPECT_EQ(s.axis[i].coord, before.axis[i].coord);
      EXPECT_EQ(s.axis[i].offset, before.axis[i].offset);
      EXPECT_EQ(s.axis[i].steps, before.axis[i].steps);
    }
    ok(g, "G91 G1");
  }
}

TEST(GcodeInterpreter, TheAxisSetIsAParameter) {
  const am::GcodeAxis uno[] = {{'X', am::kModesShield, 1600000},
                               {'Y', am::kModesShield, 1600000},
                               {'U', am::kModesUnipolar, 262144},
                               {'Z', 0, 400000}};
  am::GcodeInterpreter<4> g(uno);
  am::GcodeAction<4> a;
  EXPECT_EQ(g.run("G1 E5 F100", a), GcodeError::no_such_axis);
  ASSERT_EQ(g.run("G0 U0.5 Z1", a), GcodeError::none);
  EXPECT_EQ(a.target[2], 131);  // 0.5 mm at 262.144 units/mm
  EXPECT_EQ(a.target[3], 400);
  EXPECT_EQ(a.axes, 0xC);
  // A lathe board with Z and U only: no XY plane for arcs.
  const am::GcodeAxis lathe[] = {{'Z', 0, 400000}, {'U', am::kModesUnipolar, 4096}};
  am::GcodeInterpreter<2> l(lathe);
  am::GcodeAction<2> b;
  EXPECT_EQ(l.run("G0 X1", b), GcodeError::no_such_axis);
  ASSERT_EQ(l.run("G0 Z-2", b), GcodeError::none);
  EXPECT_EQ(b.target[0], -800);
  EXPECT_EQ(l.run("G2 Z1 I1 F100", b), GcodeError::no_such_axis);  // G17 needs X and Y
  EXPECT_EQ(l.state().axis[0].steps, -800);
}

TEST(GcodeInterpreter, PositionRange) {
  // +-10 m at 100 steps/mm is well inside.
  const am::GcodeAxis fine[] = {{'X', 0, 100000}, {'Y', 0, 100000}};
  am::GcodeInterpreter<2> g(fine);
  am::GcodeAction<2> a;
  ASSERT_EQ(g.run("G0 X10000 Y-10000", a), GcodeError::none);
  EXPECT_EQ(a.target[0], 1000000);
  EXPECT_EQ(a.target[1], -1000000);
  ASSERT_EQ(g.run("G0 X214748.3647 Y-214748.3647", a), GcodeError::none);  // the coordinate limit
  EXPECT_EQ(a.target[0], 21474836);
  EXPECT_EQ(a.target[1], -21474836);
  EXPECT_EQ(g.run("G91 G0 X0.0001", a), GcodeError::target_out_of_range);
  EXPECT_EQ(g.state().axis[0].steps, 21474836);

  // At 20000 steps/mm the steps run out first: 107374.1823 mm.
  const am::GcodeAxis dense[] = {{'X', 0, 20000000}, {'Y', 0, 20000000}};
  am::GcodeInterpreter<2> d(dense);
  ASSERT_EQ(d.run("G0 X107374.1823", a), GcodeError::none);
  EXPECT_EQ(a.target[0], 2147483646);
  EXPECT_EQ(d.run("G0 X107374.1824", a), GcodeError::target_out_of_range);  // 2147483648
  EXPECT_EQ(d.run("G0 X-107374.1824", a), GcodeError::target_out_of_range);
  EXPECT_EQ(d.state().axis[0].steps, 2147483646);
  EXPECT_EQ(d.state().axis[0].coord, 1073741823);
  // Offsets: G92 X-100000 here would need an offset of 4.1e9 steps.
  EXPECT_EQ(d.run("G92 X-100000", a), GcodeError::target_out_of_range);
  ASSERT_EQ(d.run("G92 X0", a), GcodeError::none);  // offset 2147483646
  EXPECT_EQ(d.run("G0 X0.0001", a), GcodeError::target_out_of_range);  // 2147483648 steps
  ASSERT_EQ(d.run("G0 X-107374", a), GcodeError::none);
  EXPECT_EQ(a.target[0], 3646);
  // Everything refused left the position alone.
  EXPECT_EQ(d.state().axis[0].offset, 2147483646);
}

TEST(GcodeInterpreter, UnnamedAxesKeepTheirTargets) {
  Printer g(kPrinter);
  ok(g, "G1 F100 X1 Y2 Z3 E4");
  const Action a = ok(g, "Y5");
  EXPECT_EQ(a.axes, 0x2);
  EXPECT_EQ(a.target[0], 80);
  EXPECT_EQ(a.target[1], 400);
  EXPECT_EQ(a.target[2], 1200);
  EXPECT_EQ(a.target[3], 372);
  // A zero-length move is still a move (the planner skips it).
  const Action b = ok(g, "Y5");
  EXPECT_EQ(b.kind, GcodeActionKind::move);
  EXPECT_EQ(b.target[1], 400);
}

TEST(GcodeInterpreter, ResetGoesBackToPowerUp) {
  Printer g(kPrinter);
  ok(g, "G20 G91 G1 X1 F10");
  g.reset();
  EXPECT_EQ(g.state().axis[0].steps, 0);
  EXPECT_FALSE(g.state().modal.inches);
  EXPECT_EQ(g.state().modal.feed, 0);
  EXPECT_EQ(g.index_of('Z'), 2);
  EXPECT_EQ(g.index_of('U'), am::kNoAxis);
}
