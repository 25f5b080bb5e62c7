// Firmware retraction in the interpreter (core/text/gcode_retraction.h):
// G10/G11 against a model of the rule (E by -length, then +length + extra,
// Z by +-hop, in the axes' offsets, the program positions unchanged) over a
// sweep of settings and interleaved moves; M207/M208 words, units and
// ranges; refusals that change nothing; settings put in from outside (the
// m1284's settings block) that keep the state; the codes absent without
// Retract.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <random>
#include <string>

#include "core/text/gcode_interpreter.h"

using am::GcodeError;

namespace {

// The m32 printer's axes: 1000 steps/mm each (m32_wiring.h), and an i3's
// X Y 80, Z 400, E 93.
const am::GcodeAxis kM32[] = {{'X', 0, 1000000}, {'Y', 0, 1000000}, {'Z', 0, 1000000}, {'E', 0, 1000000}};
const am::GcodeAxis kI3[] = {{'X', 0, 80000}, {'Y', 0, 80000}, {'Z', 0, 400000}, {'E', 0, 93000}};
const am::GcodeAxis kNoE[] = {{'X', 0, 1000000}, {'Y', 0, 1000000}, {'Z', 0, 1000000}};
using Grbl = am::GcodeInterpreter<4, false, true, false, false, false, true>;  // the m32-grbl image's
using Without = am::GcodeInterpreter<4, false, true, false, false, false>;     // any other
using Action = am::GcodeAction<4>;

GcodeError run(Grbl& g, const std::string& line, Action& a) { return g.run(line.c_str(), a); }

// Steps of `mm_e4` (1/10000 mm) at `spm` steps per metre, rounded half away
// from zero, in doubles: the reference, not the interpreter's arithmetic.
int64_t steps_of(int64_t mm_e4, uint32_t spm) {
  const double s = double(mm_e4) * spm / 1e7;
  return s < 0 ? -int64_t(-s + 0.5) : int64_t(s + 0.5);
}

TEST(GcodeRetraction, G10G11MoveEAndZAndKeepTheProgramPosition) {
  Grbl g(kM32);
  Action a;
  ASSERT_EQ(run(g, "G1 X10 Z0.3 E5 F1200", a), GcodeError::none);
  ASSERT_EQ(run(g, "G10", a), GcodeError::none);
  EXPECT_EQ(a.kind, am::GcodeActionKind::move);
  EXPECT_FALSE(a.rapid);
  EXPECT_EQ(a.axes, 0x08);                 // E alone (no hop by default)
  EXPECT_EQ(a.target[3], 5000 - 3000);     // Marlin's 3 mm
  EXPECT_EQ(a.coord[3], 50000 - 30000);    // the move's end in program units: timed over 3 mm
  EXPECT_EQ(a.feed, 27000000);             // 2700 mm/min
  EXPECT_EQ(g.state().axis[3].coord, 50000);  // the program's E stays
  EXPECT_EQ(g.state().axis[3].steps, 2000);
  EXPECT_TRUE(g.retraction().retracted);
  // A move while retracted keeps the filament back: E 6 is 3 mm short.
  ASSERT_EQ(run(g, "G1 X20 E6", a), GcodeError::none);
  EXPECT_EQ(a.target[3], 6000 - 3000);
  ASSERT_EQ(run(g, "G10", a), GcodeError::none);  // already retracted: nothing
  EXPECT_EQ(a.axes, 0);
  EXPECT_EQ(a.kind, am::GcodeActionKind::none);
  ASSERT_EQ(run(g, "G11", a), GcodeError::none);
  EXPECT_EQ(a.axes, 0x08);
  EXPECT_EQ(a.target[3], 6000);
  EXPECT_EQ(a.feed, 4800000);  // 480 mm/min
  ASSERT_EQ(run(g, "G11", a), GcodeError::none);  // not retracted: nothing
  EXPECT_EQ(a.axes, 0);
  // With a hop and an extra: Z up and back, E pushed 0.5 mm further.
  ASSERT_EQ(run(g, "M207 S2 F1800 Z0.4", a), GcodeError::none);
  ASSERT_EQ(run(g, "M208 S0.5 F600", a), GcodeError::none);
  ASSERT_EQ(run(g, "G10", a), GcodeError::none);
  EXPECT_EQ(a.axes, 0x0C);
  EXPECT_EQ(a.target[2], 300 + 400);
  EXPECT_EQ(a.target[3], 6000 - 2000);
  EXPECT_EQ(a.feed, 18000000);
  EXPECT_EQ(g.state().axis[2].coord, 3000);  // the program's Z stays 0.3
  ASSERT_EQ(run(g, "G1 Z0.6", a), GcodeError::none);
  EXPECT_EQ(a.target[2], 600 + 400);  // still lifted
  ASSERT_EQ(run(g, "G11", a), GcodeError::none);
  EXPECT_EQ(a.target[2], 600);
  EXPECT_EQ(a.target[3], 6500);
  EXPECT_EQ(a.feed, 6000000);
  // M207 while retracted: the G11 pushes the length in force, not the G10's.
  ASSERT_EQ(run(g, "G10", a), GcodeError::none);
  EXPECT_EQ(a.target[3], 6500 - 2000);
  ASSERT_EQ(run(g, "M207 S1.25", a), GcodeError::none);
  ASSERT_EQ(run(g, "G11", a), GcodeError::none);
  EXPECT_EQ(a.target[3], 6500 - 2000 + 1250 + 500);
  EXPECT_EQ(g.state().axis[3].offset, 500 - 2000 + 1250 + 500);
  EXPECT_EQ(g.state().axis[3].coord, 60000);
}

// The rule against a model, over random settings, hops, extras and moves
// between the codes, on the i3's scale (rounding on every axis).
TEST(GcodeRetraction, EveryRetractionFollowsTheModel) {
  std::mt19937 rng(7);
  for (int run_no = 0; run_no < 200; ++run_no) {
    Grbl g(kI3);
    Action a;
    const int32_t length = int32_t(rng() % 100000), extra = int32_t(rng() % 20000), hop = int32_t(rng() % 20000);
    char line[96];
    std::snprintf(line, sizeof line, "M207 S%d.%04d Z%d.%04d", length / 10000, length % 10000, hop / 10000, hop % 10000);
    ASSERT_EQ(run(g, line, a), GcodeError::none) << line;
    std::snprintf(line, sizeof line, "M208 S%d.%04d", extra / 10000, extra % 10000);
    ASSERT_EQ(run(g, line, a), GcodeError::none) << line;
    int64_t e_offset = 0, z_offset = 0;  // the model's
    int64_t e_prog = 0, z_prog = 0;      // program positions, 1/10000 mm
    bool retracted = false;
    for (int k = 0; k < 60; ++k) {
      const int what = int(rng() % 3);
      if (what == 0) {
        e_prog += int64_t(rng() % 50000);
        z_prog = int64_t(rng() % 100000);
        std::snprintf(line, sizeof line, "G1 Z%lld.%04lld E%lld.%04lld F900", (long long)(z_prog / 10000),
                      (long long)(z_prog % 10000), (long long)(e_prog / 10000), (long long)(e_prog % 10000));
      } else {
        const bool out = what == 1;
        std::snprintf(line, sizeof line, out ? "G10" : "G11");
        if (out != retracted) {
          e_offset += out ? -steps_of(length, 93000) : steps_of(length + extra, 93000);
          z_offset += out ? steps_of(hop, 400000) : -steps_of(hop, 400000);
          retracted = out;
        }
      }
      ASSERT_EQ(run(g, line, a), GcodeError::none) << line;
      EXPECT_EQ(g.state().axis[3].steps, steps_of(e_prog, 93000) + e_offset) << line << " run " << run_no;
      EXPECT_EQ(g.state().axis[2].steps, steps_of(z_prog, 400000) + z_offset) << line << " run " << run_no;
      EXPECT_EQ(g.state().axis[3].coord, e_prog) << line;
      EXPECT_EQ(g.state().axis[2].coord, z_prog) << line;
      EXPECT_EQ(g.retraction().retracted, retracted);
    }
  }
}

TEST(GcodeRetraction, SettingsWordsUnitsAndRanges) {
  Grbl g(kM32);
  Action a;
  ASSERT_EQ(run(g, "G20", a), GcodeError::none);
  ASSERT_EQ(run(g, "M207 S0.1 F100", a), GcodeError::none);  // inches
  EXPECT_EQ(g.retraction().length, 25400);
  EXPECT_EQ(g.retraction().feed, 25400000);
  ASSERT_EQ(run(g, "G21", a), GcodeError::none);
  const auto before = g.retraction();
  const char* refused[] = {"M207 S101", "M207 S-1", "M207 F0", "M207 F100001", "M207 Z-0.1", "M208 S100.0001",
                           "M208 F-5",  "M208 Z1",  "M207 X1", "M207 E1",      "G10 E1",     "G11 X0",
                           "G10 P1",    "G10 G1",   "G11 M82", "M207 S1 G4 P1"};
  const GcodeError why[] = {GcodeError::out_of_range, GcodeError::out_of_range, GcodeError::out_of_range,
                            GcodeError::out_of_range, GcodeError::out_of_range, GcodeError::out_of_range,
                            GcodeError::out_of_range, GcodeError::unused_word,  GcodeError::unused_word,
                            GcodeError::unused_word,  GcodeError::unused_word,  GcodeError::unused_word,
                            GcodeError::unused_word,  GcodeError::multiple_actions, GcodeError::multiple_actions,
                            GcodeError::unused_word};
  for (size_t i = 0; i < sizeof refused / sizeof *refused; ++i) {
    EXPECT_EQ(run(g, refused[i], a), why[i]) << refused[i];
    EXPECT_EQ(g.retraction().length, before.length) << refused[i];
    EXPECT_EQ(g.retraction().feed, before.feed) << refused[i];
    EXPECT_EQ(g.retraction().hop, before.hop) << refused[i];
    EXPECT_EQ(g.retraction().extra, before.extra) << refused[i];
    EXPECT_FALSE(g.retraction().retracted) << refused[i];
    EXPECT_EQ(g.state().axis[3].steps, 0) << refused[i];
  }
  ASSERT_EQ(run(g, "N7 M208 F300", a), GcodeError::none);  // a word not given keeps its value
  EXPECT_EQ(g.retraction().recover_feed, 3000000);
  EXPECT_EQ(g.retraction().extra, before.extra);
  // No E axis: G10 has nothing to pull.
  am::GcodeInterpreter<3, false, true, false, false, false, true> mill(kNoE);
  am::GcodeAction<3> m;
  EXPECT_EQ(mill.run("G10", m), GcodeError::no_such_axis);
}

TEST(GcodeRetraction, AbsentWithoutRetract) {
  Without g(kM32);
  Action a;
  for (const char* line : {"G10", "G11", "M207 S1", "M208 S1"}) EXPECT_EQ(g.run(line, a), GcodeError::unsupported_code) << line;
  am::GcodeBlock b;
  EXPECT_EQ(am::parse_gcode<true>("G10", b), GcodeError::unsupported_code);
  EXPECT_EQ((am::parse_gcode<true, true>("G10", b)), GcodeError::none);
}

// Settings put in from outside (the settings block's, at boot or after
// M502) keep the state: a G11 after them pushes the new length and extra,
// and the Without interpreter answers Marlin's defaults and takes nothing.
TEST(GcodeRetraction, SettingsFromOutsideKeepTheState) {
  Grbl g(kM32);
  Action a;
  ASSERT_EQ(run(g, "G10", a), GcodeError::none);  // E -3 mm
  am::GcodeRetraction r;
  r.length = 45000;
  r.extra = 2000;
  r.recover_feed = 6000000;
  r.retracted = false;  // not what the interpreter's state is: kept as it is
  g.set_retraction(r);
  EXPECT_TRUE(g.retraction().retracted);
  EXPECT_EQ(g.retraction().length, 45000);
  ASSERT_EQ(run(g, "G11", a), GcodeError::none);
  EXPECT_EQ(a.target[3], -3000 + 4500 + 200);  // the new length and extra
  EXPECT_EQ(a.feed, 6000000);
  Without w(kM32);
  w.set_retraction(r);
  EXPECT_EQ(w.retraction().length, am::GcodeRetraction().length);
  EXPECT_EQ(w.run("G10", a), GcodeError::unsupported_code);
}

}  // namespace
