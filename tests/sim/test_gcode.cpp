// G-code on the real images (docs/gcode.md): programs end exactly where their
// numbers say, every refused line changes nothing, G4 is timed by the step
// timer.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "schedule.h"
#include "sim_fixture.h"

namespace {

uint64_t next_random(uint64_t& state) {
  state = state * 6364136223846793005ull + 1442695040888963407ull;
  return state >> 33;
}

// Steps for a program coordinate in 1/10000 mm (the interpreter's unit) at
// 1000 steps/mm, rounded half away from zero: an independent reference, in
// integers so no binary fraction can tip a half.
int64_t steps_of(int64_t coord) { return coord < 0 ? -((-coord + 5) / 10) : (coord + 5) / 10; }

// A coordinate in 1/10000 mm as G-code text with four decimals.
std::string mm(int64_t coord) {
  char buf[32];
  const int64_t mag = coord < 0 ? -coord : coord;
  std::snprintf(buf, sizeof buf, "%s%lld.%04lld", coord < 0 ? "-" : "", (long long)(mag / 10000),
                (long long)(mag % 10000));
  return buf;
}

}  // namespace

TEST(Gcode, ASlicerStyleProgramEndsExactlyOnItsTargets) {
  // A printer-like job on the m32 (1000 steps/mm on X Y Z E): a polyline of
  // short G1 moves with extrusion, travel moves, retractions, G92 E0 resets,
  // a stretch in inches and one in relative mode, feed changes. The test
  // keeps its own model of the program position (1/10000 mm, integers) and
  // checks every axis at the end against the rounded steps.
  uint64_t state = 7;
  std::vector<std::string> lines = {"G21", "G90", "M82", "G92 E0", "G1 Z0.3 F600"};
  // E: G92 E0 restarts the coordinate and keeps the machine's steps, so the
  // machine ends at the sum of the rounded steps at every reset, plus the
  // last stretch's.
  int64_t x = 0, y = 0, z = 3000, e = 0, e_steps = 0;
  for (int k = 0; k < 120; ++k) {
    const int64_t nx = 100000 + int64_t(next_random(state) % 40000) - 20000;
    const int64_t ny = 100000 + int64_t(next_random(state) % 40000) - 20000;
    const int kind = int(next_random(state) % 10);
    if (kind == 0) {  // retract, travel, unretract
      lines.push_back("G1 E" + mm(e - 8000) + " F2400");
      lines.push_back("G0 X" + mm(nx) + " Y" + mm(ny));
      lines.push_back("G1 E" + mm(e));
    } else if (kind == 1) {  // a reset of E
      lines.push_back("G92 E0");
      e_steps += steps_of(e);
      e = 0;
      continue;
    } else {
      e += int64_t(next_random(state) % 300);
      lines.push_back("G1 X" + mm(nx) + " Y" + mm(ny) + " E" + mm(e) + " F" +
                      std::to_string(1200 + 300 * int(next_random(state) % 8)));
    }
    x = nx;
    y = ny;
  }
  // Inches, relative: 0.05 in = 1.27 mm in X, -0.1 in in Y.
  lines.insert(lines.end(), {"G20", "G91", "G1 X0.05 Y-0.1 F20", "G90", "G21"});
  x += 12700;
  y -= 25400;
  lines.push_back("G1 Z1.3 F600");
  z = 13000;
  lines.push_back("M400");  // M114's counts are where the motors are now: after the motion
  lines.push_back("M114");
  e_steps += steps_of(e);

  auto m = simtest::run("m32", lines, 300);
  EXPECT_TRUE(m->serial().errors().empty()) << m->serial().errors().front();
  EXPECT_EQ(m->serial().lines_ok(), lines.size());
  EXPECT_EQ(int64_t(m->axis('X')->steps()), steps_of(x));
  EXPECT_EQ(int64_t(m->axis('Y')->steps()), steps_of(y));
  EXPECT_EQ(int64_t(m->axis('Z')->steps()), steps_of(z));
  EXPECT_EQ(int64_t(m->axis('E')->steps()), e_steps);
  // M114 reports the same machine counts.
  const std::vector<std::string> msgs = m->serial().messages();
  ASSERT_FALSE(msgs.empty());
  std::ostringstream count;
  count << "Count X:" << steps_of(x) << " Y:" << steps_of(y) << " Z:" << steps_of(z) << " E:" << e_steps;
  EXPECT_NE(msgs.back().find(count.str()), std::string::npos) << msgs.back();
}

// The M114 reports among the lines received (refusals print a reason line).
std::vector<std::string> reports(const sim::SerialHost& host) {
  std::vector<std::string> out;
  for (const std::string& l : host.messages())
    if (l.rfind("X:", 0) == 0) out.push_back(l);
  return out;
}

TEST(Gcode, RefusedLinesAreAnsweredOnceAndChangeNothing) {
  // One line per kind of refusal, between two position reports: each gets
  // its error, nothing moves, and the reports agree. In both styles: the
  // printer's Marlin (`Error:<reason>`, then ok; an unknown code is an
  // `echo:` and ok, as Marlin answers it) and the m32-cnc's grbl (the reason
  // as `[MSG:...]`, then `error:<grbl's number>`).
  struct Bad {
    std::string line, reason;
    int grbl;
  };
  const std::vector<Bad> bad = {
      {"G1 X1 L3", "unsupported word letter", 20},
      {"G1 X1 X2", "word given twice", 25},
      {"G0 G1 X1", "two codes of one modal group", 21},
      {"G1 X1.2.3", "bad number", 2},
      {"G7 X1", "unsupported G or M code", 20},
      {"G1 X1 F0", "feed rate must be above 0", 22},
      {"G1 A5", "no such axis on this board", 20},
      {"G4", "G4 needs its time word", 28},
      {"G2 X3 Y2 I1 J0", "G2/G3 arcs are not in this board's image", 20},  // the printer only
      {"G1 X1 P2 F100", "word not used by any code on the line", 36},
      {"G1 X300000", "number out of range", 100},
      {"G1 X1 (open", "comment not closed", 101},
  };
  for (const char* image : {"m32", "m32-cnc"}) {
    SCOPED_TRACE(image);
    const bool marlin = std::string(image) == "m32";
    std::vector<std::string> lines = {"G21", "G90", "G1 X1 Y2 F600", "M400", "M114"};
    std::vector<Bad> cases;
    for (const Bad& b : bad)
      if (marlin || b.line[1] != '2') cases.push_back(b);  // the m32-cnc has arcs
    for (const Bad& b : cases) lines.push_back(b.line);
    lines.push_back("M114");
    auto m = simtest::run(image, lines, 20);
    const std::vector<sim::Response>& r = m->serial().responses();
    ASSERT_EQ(r.size(), lines.size());
    std::vector<std::string> unknown;
    for (size_t i = 0; i < cases.size(); ++i) {
      const Bad& b = cases[i];
      if (marlin && b.line == "G7 X1") {
        EXPECT_EQ(r[5 + i].answer, "ok");
        unknown.push_back("echo:Unknown command: \"" + b.line + "\"");
      } else {
        EXPECT_EQ(r[5 + i].answer, marlin ? "Error:" + b.reason : "error:" + std::to_string(b.grbl)) << b.line;
        EXPECT_EQ(r[5 + i].reason, b.reason) << b.line;
      }
    }
    if (marlin) {
      size_t echoes = 0;
      for (const std::string& l : m->serial().messages()) echoes += l == unknown[0];
      EXPECT_EQ(echoes, 1u);
    }
    const std::vector<std::string> msgs = reports(m->serial());
    ASSERT_EQ(msgs.size(), 2u);
    EXPECT_EQ(msgs[0], msgs[1]);
    EXPECT_EQ(m->axis('X')->steps(), 1000.0);
    EXPECT_EQ(m->axis('Y')->steps(), 2000.0);
  }
}

TEST(Gcode, TheTimerPulsedAxisMovesAloneAndTheRefusalChangesNothing) {
  // The Uno's image has no arcs (flash): a G2 is refused whole as well.
  auto m = simtest::run("uno", {"G1 X4 Y2 F600", "G1 X8 Z1 F600", "M114", "G1 Z0.5 F300", "G2 X6 Y4 I2 J0", "M114"},
                        20);
  const std::vector<sim::Response>& r = m->serial().responses();
  ASSERT_EQ(r.size(), 6u);
  EXPECT_EQ(r[1].answer, "error:109");
  EXPECT_EQ(r[1].reason, "the hardware-timed axis moves alone");
  EXPECT_EQ(r[4].answer, "error:20");
  EXPECT_EQ(r[4].reason, "G2/G3 arcs are not in this board's image");
  // The shield axes: 25 steps/mm; Z: 400 steps/mm.
  EXPECT_EQ(m->axis('X')->steps(), 100.0);
  EXPECT_EQ(m->axis('Y')->steps(), 50.0);
  EXPECT_EQ(m->axis('Z')->steps(), 200.0);
  const std::vector<std::string> msgs = reports(m->serial());
  ASSERT_EQ(msgs.size(), 2u);
  EXPECT_NE(msgs[0].find("X:4.0000 Y:2.0000"), std::string::npos) << msgs[0];
}

TEST(Gcode, G4DwellsToTheTickBetweenMovesOfTheSameAxes) {
  // The dwell is queued in the step engine: the next move's first step comes
  // exactly P seconds plus its own first interval after the last step of
  // the move before, for several P. On the Uno's Z axis, whose edges the
  // timer makes, that holds to the cycle.
  for (const char* p : {"0.001", "0.25", "1.5", "70"}) {
    auto m = simtest::run("uno", {"G1 Z0.25 F600", std::string("G4 P") + p, "G1 Z0.5 F600"}, 90);
    const auto& st = m->axis('Z')->step_cycles;
    ASSERT_EQ(st.size(), 200u);
    const uint64_t ms = uint64_t(std::lround(std::atof(p) * 1000));
    // The second move: 100 steps at F600 (10 mm/s = 4000 steps/s) with the
    // board's default acceleration (800 steps/s^2).
    const std::vector<uint32_t> second = sim::planned_schedule(100, sim::Ramp{16000000, 4000, 800});
    ASSERT_EQ(second.size(), 100u);
    EXPECT_EQ(st[100] - st[99], ms * 16000 + second[0]) << "P" << p;
  }
}

TEST(Gcode, AnImageWithoutCoilAxesHasNoM350) {
  // Every m32 axis is step/dir (its microsteps are the drivers' jumpers): M350
  // is not in those images. grbl style: unsupported, error:20; Marlin style:
  // Marlin's answer to a code it was built without. The line changes nothing.
  auto grbl = simtest::run("m32-cnc", {"M350 X16", "G1 X1 F600"}, 30);
  const std::vector<sim::Response>& g = grbl->serial().responses();
  ASSERT_EQ(g.size(), 2u);
  EXPECT_EQ(g[0].answer, "error:20");
  EXPECT_EQ(g[0].reason, "unsupported G or M code");
  EXPECT_EQ(g[1].answer, "ok");
  EXPECT_EQ(grbl->axis('X')->steps(), 1000.0);
  auto marlin = simtest::run("m32", {"M350 X16", "G1 X1 F600"}, 30);
  const std::vector<sim::Response>& r = marlin->serial().responses();
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].answer, "ok");
  const std::vector<std::string>& msgs = marlin->serial().messages();
  EXPECT_NE(std::find(msgs.begin(), msgs.end(), "echo:Unknown command: \"M350 X16\""), msgs.end());
  EXPECT_EQ(marlin->axis('X')->steps(), 1000.0);
}

TEST(Gcode, TargetsMeanTheSameInEveryExcitationModeAndBesideMove) {
  // Uno shield X: 25 full steps per mm. In 16 microsteps a G-code millimetre
  // is still 25 full steps (400 microsteps); a MOVE in between moves the
  // motor, and the next G-code target is reached from where it really is.
  auto m = simtest::run("uno", {"M350 X16", "G1 X1 F60", "MOVE X80", "G1 X2 F60", "POS", "M114"}, 60);
  const std::vector<sim::Response>& r = m->serial().responses();
  ASSERT_EQ(r.size(), 6u);
  for (const sim::Response& x : r) EXPECT_EQ(x.answer, "ok") << x.line;
  // 80 microsteps = 5 full steps; then to 2 mm = 50 full steps.
  EXPECT_EQ(m->axis('X')->steps(), 50.0);
  const std::vector<std::string> msgs = m->serial().messages();
  ASSERT_EQ(msgs.size(), 2u);
  EXPECT_NE(msgs[0].find("X:50 "), std::string::npos) << msgs[0];  // POS, at rest
  EXPECT_NE(msgs[1].find("X:2.0000"), std::string::npos) << msgs[1];
  EXPECT_NE(msgs[1].find("Count X:50 "), std::string::npos) << msgs[1];
}
