// core/text/gcode_interpreter.h: modes, units, distance modes, G92, the
// extruder's own distance mode, feed, dwell, the M-functions, the axis set as
// a parameter and the position range. Sequences are checked against a model
// in doubles written from docs/gcode.md, not from the code.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "core/text/gcode_interpreter.h"

using am::GcodeActionKind;
using am::GcodeError;

namespace {

// A printer: 80 steps/mm on X and Y, 400 on Z, 93 on E.
const am::GcodeAxis kPrinter[] = {{'X', 0, 80000}, {'Y', 0, 80000}, {'Z', 0, 400000}, {'E', 0, 93000}};
using Printer = am::GcodeInterpreter<4>;
using Action = am::GcodeAction<4>;

GcodeError run(Printer& g, const char* line, Action& a) { return g.run(line, a); }
Action ok(Printer& g, const char* line) {
  Action a;
  const GcodeError e = g.run(line, a);
  EXPECT_EQ(e, GcodeError::none) << line << ": " << am::gcode_error_message(e);
  return a;
}

}  // namespace

TEST(GcodeInterpreter, PowerUpState) {
  Printer g(kPrinter);
  const auto& s = g.state();
  EXPECT_EQ(s.modal.motion, am::Motion::rapid);
  EXPECT_EQ(s.modal.plane, am::Plane::xy);
  EXPECT_FALSE(s.modal.incremental);
  EXPECT_FALSE(s.modal.inches);
  EXPECT_FALSE(s.modal.e_relative);
  EXPECT_EQ(s.modal.feed, 0);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(s.axis[i].coord, 0);
    EXPECT_EQ(s.axis[i].offset, 0);
    EXPECT_EQ(s.axis[i].steps, 0);
  }
  // Axis words alone move in the power-up motion mode, G0, without an F.
  const Action a = ok(g, "X1 Y-2");
  EXPECT_EQ(a.kind, GcodeActionKind::move);
  EXPECT_TRUE(a.rapid);
  EXPECT_EQ(a.target[0], 80);
  EXPECT_EQ(a.target[1], -160);
  EXPECT_EQ(a.axes, 0x3);
}

TEST(GcodeInterpreter, InchesAreExact) {
  Printer g(kPrinter);
  Action a = ok(g, "G20 G0 X1");
  EXPECT_EQ(a.target[0], 2032);  // 25.4 mm * 80
  EXPECT_EQ(a.coord[0], 254000);
  a = ok(g, "Y-0.0005");  // -0.0127 mm = -1.016 steps
  EXPECT_EQ(a.target[1], -1);
  EXPECT_EQ(a.coord[1], -127);
  a = ok(g, "G21 X1");  // back in mm
  EXPECT_EQ(a.target[0], 80);
  // Feed in inches per minute is kept in mm per minute.
  a = ok(g, "G20 G1 X2 F10");
  EXPECT_EQ(a.feed, 2540000);  // 254 mm/min
  EXPECT_EQ(a.target[0], 4064);
  a = ok(g, "G21 X0");  // F is kept across G21 (already in mm/min)
  EXPECT_EQ(a.feed, 2540000);
}

TEST(GcodeInterpreter, RoundingToStepsIsHalfAwayFromZero) {
  Printer g(kPrinter);
  Action a = ok(g, "G0 X0.00625");  // 0.5 step
  EXPECT_EQ(a.target[0], 1);
  a = ok(g, "X-0.00625");
  EXPECT_EQ(a.target[0], -1);
  a = ok(g, "X0.0062");  // 0.496 step
  EXPECT_EQ(a.target[0], 0);
  a = ok(g, "X0.00005");  // 0.1 um (the resolution), rounded from 0.05 um
  EXPECT_EQ(a.coord[0], 1);
  a = ok(g, "X-0.00005");
  EXPECT_EQ(a.coord[0], -1);
}

TEST(GcodeInterpreter, IncrementalMovesDoNotAccumulateRounding) {
  Printer g(kPrinter);
  ok(g, "G91 G1 F100");
  Action a;
  for (int i = 0; i < 1000; ++i) a = ok(g, "X0.001");  // 0.08 step each
  EXPECT_EQ(a.target[0], 80);  // 1 mm, not 0
  EXPECT_EQ(a.coord[0], 10000);
}

TEST(GcodeInterpreter, ModalStateChangesOnlyWhatTheLineSays) {
  Printer g(kPrinter);
  ok(g, "G1 F600");
  EXPECT_EQ(g.state().modal.motion, am::Motion::linear);
  EXPECT_EQ(g.state().modal.feed, 6000000);
  ok(g, "G18");
  EXPECT_EQ(g.state().modal.plane, am::Plane::zx);
  EXPECT_EQ(g.state().modal.motion, am::Motion::linear);
  ok(g, "G19");
  EXPECT_EQ(g.state().modal.plane, am::Plane::yz);
  ok(g, "G17 G91");
  EXPECT_TRUE(g.state().modal.incremental);
  EXPECT_EQ(g.state().modal.plane, am::Plane::xy);
  ok(g, "G94");  // the only feed mode: accepted, nothing changes
  EXPECT_TRUE(g.state().modal.incremental);
  EXPECT_EQ(g.state().modal.feed, 6000000);
  // A modal code with an action on its line.
  const Action a = ok(g, "G90 G0 X5");
  EXPECT_FALSE(g.state().modal.incremental);
  EXPECT_EQ(a.target[0], 400);
  EXPECT_TRUE(a.rapid);
  // A line with only modes is an action of kind none.
  EXPECT_EQ(ok(g, "G21 G90 G17").kind, GcodeActionKind::none);
  EXPECT_EQ(ok(g, "").kind, GcodeActionKind::none);
  EXPECT_EQ(ok(g, "N5 (comment)").kind, GcodeActionKind::none);
}

TEST(GcodeInterpreter, ExtruderDistanceMode) {
  Printer g(kPrinter);
  ok(g, "G1 F1200 E1");  // absolute: E at 1 mm
  EXPECT_EQ(g.state().axis[3].steps, 93);
  ok(g, "M83");  // E relative, X Y Z still absolute
  Action a = ok(g, "X1 E1");
  EXPECT_EQ(a.target[3], 186);
  a = ok(g, "X1 E1");
  EXPECT_EQ(a.target[0], 80);  // X absolute: no change
  EXPECT_EQ(a.target[3], 279);
  ok(g, "G90");  // as in Marlin, G90 makes E absolute again
  a = ok(g, "E1");
  EXPECT_EQ(a.target[3], 93);
  ok(g, "G91");  // and G91 relative
  a = ok(g, "X1 E1");
  EXPECT_EQ(a.target[0], 160);
  EXPECT_EQ(a.target[3], 186);
  ok(g, "M82");  // E absolute, X still relative
  a = ok(g, "X1 E1");
  EXPECT_EQ(a.target[0], 240);
  EXPECT_EQ(a.target[3], 93);
  // On one line G90/G91 first, then M82/M83.
  ok(g, "G90 M83");
  EXPECT_FALSE(g.state().modal.incremental);
  EXPECT_TRUE(g.state().modal.e_relative);
  ok(g, "M82 G91");
  EXPECT_TRUE(g.state().modal.incremental);
  EXPECT_FALSE(g.state().modal.e_relative);
}

TEST(GcodeInterpreter, G92SetsTheProgramPositionAndKeepsTheMachine) {
  Printer g(kPrinter);
  ok(g, "G1 F3000 X10 E5");
  Action a = ok(g, "G92 X0 E0");
  EXPECT_EQ(a.kind, GcodeActionKind::set_position);
  EXPECT_EQ(a.axes, 0x9);
  EXPECT_EQ(a.target[0], 800);  // nothing moves
  EXPECT_EQ(a.target[3], 465);
  EXPECT_EQ(a.coord[0], 0);
  EXPECT_EQ(g.state().axis[0].offset, 800);
  a = ok(g, "X1 E1");
  EXPECT_EQ(a.target[0], 880);
  EXPECT_EQ(a.target[3], 558);
  // G92 values are absolute whatever G91/M83 say.
  ok(g, "G91 M83");
  ok(g, "G92 X100");
  a = ok(g, "X-1");
  EXPECT_EQ(a.coord[0], 990000);
  EXPECT_EQ(a.target[0], 800);
  // In inches.
  ok(g, "G90 G20 G92 Y1");
  EXPECT_EQ(g.state().axis[1].coord, 254000);
  EXPECT_EQ(g.state().axis[1].offset, -2032);
}

TEST(GcodeInterpreter, G28NamesTheAxesToHomeAndChangesNothing) {
  Printer g(kPrinter);
  ok(g, "G1 F3000 X10 Y-4 E5");
  ok(g, "G92 X1");
  const am::GcodeState<4> before = g.state();
  Action a = ok(g, "G28");
  EXPECT_EQ(a.kind, GcodeActionKind::home);
  EXPECT_EQ(a.axes, 0);  // every axis that can be homed
  a = ok(g, "G28 X0 Z7.5");  // the values are not used
  EXPECT_EQ(a.kind, GcodeActionKind::home);
  EXPECT_EQ(a.axes, 0x5);
  for (uint8_t i = 0; i < 4; ++i) {
    EXPECT_EQ(g.state().axis[i].coord, before.axis[i].coord);
    EXPECT_EQ(g.state().axis[i].offset, before.axis[i].offset);
    EXPECT_EQ(g.state().axis[i].steps, before.axis[i].steps);
  }
  Action b;
  EXPECT_EQ(run(g, "G28 G1 X0", b), GcodeError::axis_conflict);
  EXPECT_EQ(run(g, "G28 X0 F100 P1", b), GcodeError::unused_word);
  EXPECT_EQ(run(g, "G28 M17", b), GcodeError::multiple_actions);
  EXPECT_EQ(run(g, "G28 X", b), GcodeError::bad_number);
  EXPECT_EQ(run(g, "G28 A0", b), GcodeError::no_such_axis);
  // The machine homed X and Z to machine steps 40 and -7: the G92 offset of
  // X goes, the program positions follow the steps; Y and E keep theirs.
  const int32_t homed[4] = {40, 999, -7, 999};
  g.set_homed(0x5, homed);
  EXPECT_EQ(g.state().axis[0].steps, 40);
  EXPECT_EQ(g.state().axis[0].offset, 0);
  EXPECT_EQ(g.state().axis[0].coord, 5000);    // 40 / 80 mm
  EXPECT_EQ(g.state().axis[2].coord, -175);    // -7 / 400 mm
  EXPECT_EQ(g.state().axis[1].steps, before.axis[1].steps);
  EXPECT_EQ(g.state().axis[3].steps, before.axis[3].steps);
  a = ok(g, "G1 X1");
  EXPECT_EQ(a.target[0], 80);
  a = ok(g, "M999");
  EXPECT_EQ(a.kind, GcodeActionKind::unlock);
}

TEST(GcodeInterpreter, SequencesMatchADoubleModel) {
  // The model: per axis the program position in mm (double) and the G92
  // offset in steps; steps = round(coord * steps/mm) + offset, half away from
  // zero; inch words are taken to the nearest 0.1 um first (docs/gcode.md,
  // units and rounding). Step fractions here are multiples of 1e-4, so a
  // nudge of 1e-7 away from zero only settles the halves that binary
  // doubles blur.
  const double spmm[4] = {80, 80, 400, 93};
  const char letters[4] = {'X', 'Y', 'Z', 'E'};
  auto steps_of = [&](double mm, int i) { return std::llround(mm * spmm[i] + std::copysign(1e-7, mm)); };
  std::mt19937 rng(92);
  for (int run_no = 0; run_no < 200; ++run_no) {
    Printer g(kPrinter);
    double coord[4] = {0, 0, 0, 0};
    long long offset[4] = {0, 0, 0, 0};
    long long steps[4] = {0, 0, 0, 0};
    bool incremental = false, inches = false, e_relative = false;
    ok(g, "G1 F1000");
    for (int n = 0; n < 60; ++n) {
      std::string line;
      const int kind = rng() % 10;
      if (kind == 0) {
        line = incremental ? "G90" : "G91";
        incremental = !incremental;
        e_relative = incremental;  // G90/G91 set E too
      } else if (kind == 1) {
        line = inches ? "G21" : "G20";
        inches = !inches;
      } else if (kind == 2) {
        line = e_relative ? "M82" : "M83";
        e_relative = !e_relative;
      }
      const bool g92 = kind == 3;
      if (g92) line += "G92";
      bool named[4];
      for (int i = 0; i < 4; ++i) named[i] = rng() % 2;
      if (g92) named[rng() % 4] = true;
      double value[4] = {0, 0, 0, 0};
      for (int i = 0; i < 4; ++i) {
        if (!named[i]) continue;
        // Four decimals, within +-150 mm or +-5 in.
        const long long ticks = (long long)(rng() % 3000001) - 1500000;
        value[i] = inches ? std::round(ticks / 30.0) / 1e4 : ticks / 1e4;
        char word[32];
        std::snprintf(word, sizeof word, " %c%.4f", letters[i], value[i]);
        line += word;
      }
      Action a;
      const GcodeError e = run(g, line.c_str(), a);
      ASSERT_EQ(e, GcodeError::none) << line << ": " << am::gcode_error_message(e);
      for (int i = 0; i < 4; ++i) {
        if (!named[i]) continue;
        const double mm = inches ? std::round(value[i] * 25.4 * 1e4) / 1e4 : value[i];
        if (g92) {
          coord[i] = mm;
          offset[i] = steps[i] - steps_of(coord[i], i);
        } else {
          const bool rel = letters[i] == 'E' ? e_relative : incremental;
          coord[i] = rel ? coord[i] + mm : mm;
          steps[i] = steps_of(coord[i], i) + offset[i];
        }
      }
      for (int i = 0; i < 4; ++i) {
        EXPECT_NEAR(a.coord[i] / 1e4, coord[i], 1e-7) << line << " axis " << letters[i];
        EXPECT_EQ(a.target[i], steps[i]) << line << " axis " << letters[i];
        EXPECT_EQ(g.state().axis[i].offset, offset[i]) << line << " axis " << letters[i];
      }
    }
  }
}

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
