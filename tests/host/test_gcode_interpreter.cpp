// core/text/gcode_interpreter.h: modes, units, distance modes, G92, G28 and
// the extruder's own distance mode. Sequences are checked against a model
// in doubles written from docs/gcode.md, not from the code.
//
// Feed, dwell, the M-functions, program end, the axis set as a parameter,
// the position range and reset: test_gcode_interpreter_functions.cpp; the
// printer: gcode_printer.h.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
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

