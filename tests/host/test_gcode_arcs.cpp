// G2/G3 in core/text/gcode_interpreter.h against geometry done here in
// doubles a different way: for R arcs both circles through start and end are
// built and the one whose swept angle (by atan2, in the arc's direction) is
// below / above 180 degrees is taken; I/J/K arcs by distances. Also full
// circles, the end-point tolerance, the half-circle fallback, the G18/G19
// planes, helices and arcs with G92 offsets.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "core/text/gcode_interpreter.h"

using am::GcodeActionKind;
using am::GcodeError;

namespace {

const am::GcodeAxis kAxes[] = {{'X', 0, 80000}, {'Y', 0, 100000}, {'Z', 0, 400000}, {'E', 0, 93000}};
using Interp = am::GcodeInterpreter<4>;
using Action = am::GcodeAction<4>;
constexpr double kPi = 3.14159265358979323846;

Action ok(Interp& g, const std::string& line) {
  Action a;
  const GcodeError e = g.run(line.c_str(), a);
  EXPECT_EQ(e, GcodeError::none) << line << ": " << am::gcode_error_message(e);
  return a;
}

std::string fmt(const char* f, double a, double b = 0, double c = 0, double d = 0) {
  char buf[160];
  std::snprintf(buf, sizeof buf, f, a, b, c, d);
  return buf;
}

// Counter-clockwise angle swept from s to e around c in (0, 2 pi].
double ccw_sweep(double cx, double cy, double sx, double sy, double ex, double ey) {
  double d = std::atan2(ey - cy, ex - cx) - std::atan2(sy - cy, sx - cx);
  while (d <= 0) d += 2 * kPi;
  while (d > 2 * kPi) d -= 2 * kPi;
  return d;
}

// The centre of the R arc from s to e in the plane's (first, second) axes.
void reference_centre(double sx, double sy, double ex, double ey, double r, bool cw, double& cx, double& cy) {
  const double mx = (sx + ex) / 2, my = (sy + ey) / 2, dx = ex - sx, dy = ey - sy;
  const double c = std::hypot(dx, dy);
  const double h = std::sqrt(std::max(0.0, r * r - c * c / 4));
  const double cand[2][2] = {{mx - h * dy / c, my + h * dx / c}, {mx + h * dy / c, my - h * dx / c}};
  for (const auto& k : cand) {
    double sweep = ccw_sweep(k[0], k[1], sx, sy, ex, ey);
    if (cw) sweep = 2 * kPi - sweep;
    if ((r > 0) == (sweep <= kPi)) {
      cx = k[0];
      cy = k[1];
      return;
    }
  }
  ADD_FAILURE() << "no candidate";
}

}  // namespace

TEST(GcodeArcs, QuarterCirclesByHand) {
  // From (0,0) to (5,5), R5: clockwise the short way turns round (5,0),
  // counter-clockwise round (0,5); R-5 swaps them (270 degrees).
  struct Case {
    const char* line;
    int32_t i, j;
  } cases[] = {{"G2 X5 Y5 R5", 50000, 0}, {"G3 X5 Y5 R5", 0, 50000}, {"G2 X5 Y5 R-5", 0, 50000},
               {"G3 X5 Y5 R-5", 50000, 0}};
  for (const Case& c : cases) {
    Interp g(kAxes);
    const Action a = ok(g, std::string("F100 ") + c.line);
    ASSERT_EQ(a.kind, GcodeActionKind::arc) << c.line;
    EXPECT_EQ(a.clockwise, c.line[1] == '2') << c.line;
    EXPECT_EQ(a.centre_length[0], c.i) << c.line;
    EXPECT_EQ(a.centre_length[1], c.j) << c.line;
    EXPECT_EQ(a.centre[0], c.i * 8 / 1000) << c.line;   // 80 steps/mm
    EXPECT_EQ(a.centre[1], c.j * 10 / 1000) << c.line;  // 100 steps/mm
    EXPECT_EQ(a.radius, 50000) << c.line;
    EXPECT_EQ(a.target[0], 400);
    EXPECT_EQ(a.target[1], 500);
    EXPECT_EQ(a.plane_axis[0], 0);
    EXPECT_EQ(a.plane_axis[1], 1);
    EXPECT_EQ(a.plane_axis[2], 2);
    EXPECT_EQ(a.feed, 1000000);
  }
}

TEST(GcodeArcs, RandomRArcsMatchTheGeometry) {
  std::mt19937 rng(3);
  int long_arcs = 0, short_arcs = 0;
  double worst = 0;
  for (int n = 0; n < 4000; ++n) {
    Interp g(kAxes);
    auto coord = [&](double range) { return std::round((double(rng()) / 4294967295.0 * 2 - 1) * range * 1e4) / 1e4; };
    const double sx = coord(150), sy = coord(150);
    double ex, ey;
    do {
      ex = coord(150), ey = coord(150);
    } while (std::hypot(ex - sx, ey - sy) < 1);
    const double c = std::hypot(ex - sx, ey - sy);
    double r = std::round((c / 2) * (1.0001 + 4.0 * rng() / 4294967295.0) * 1e4) / 1e4;
    if (rng() % 2) r = -r;
    const bool cw = rng() % 2;
    ok(g, fmt("G0 X%.4f Y%.4f", sx, sy));
    const std::string line = fmt(cw ? "G2 X%.4f Y%.4f R%.4f F500" : "G3 X%.4f Y%.4f R%.4f F500", ex, ey, r) +
                             fmt(" (from %.4f %.4f)", sx, sy);
    const Action a = ok(g, line);
    ASSERT_EQ(a.kind, GcodeActionKind::arc) << line;
    double cx, cy;
    reference_centre(sx, sy, ex, ey, r, cw, cx, cy);
    // The centre to its resolution, 0.1 um (it is rounded to it); both ends
    // on its circle to 0.15 um.
    EXPECT_NEAR(a.centre_length[0] / 1e4, cx - sx, 1e-4) << line;
    EXPECT_NEAR(a.centre_length[1] / 1e4, cy - sy, 1e-4) << line;
    const double ux = sx + a.centre_length[0] / 1e4, uy = sy + a.centre_length[1] / 1e4;
    EXPECT_NEAR(std::hypot(sx - ux, sy - uy), std::fabs(r), 1.5e-4) << line;
    EXPECT_NEAR(std::hypot(ex - ux, ey - uy), std::fabs(r), 1.5e-4) << line;
    worst = std::max(worst, std::max(std::fabs(a.centre_length[0] / 1e4 - (cx - sx)),
                                     std::fabs(a.centre_length[1] / 1e4 - (cy - sy))));
    EXPECT_EQ(a.radius, std::llround(std::fabs(r) * 1e4)) << line;
    // The centre in steps, relative to the start's steps.
    EXPECT_NEAR(a.centre[0], (cx - sx) * 80, 1.0) << line;
    EXPECT_NEAR(a.centre[1], (cy - sy) * 100, 1.0) << line;
    EXPECT_EQ(a.target[0], std::llround(ex * 80 + std::copysign(1e-7, ex))) << line;
    EXPECT_EQ(a.target[1], std::llround(ey * 100 + std::copysign(1e-7, ey))) << line;
    // The sweep the arc's direction gives is short for R > 0, long for R < 0.
    double sweep = ccw_sweep(ux, uy, sx, sy, ex, ey);
    if (cw) sweep = 2 * kPi - sweep;
    if (r > 0) {
      EXPECT_LE(sweep, kPi + 1e-6) << line;
      ++short_arcs;
    } else {
      EXPECT_GE(sweep, kPi - 1e-6) << line;
      ++long_arcs;
    }
  }
  EXPECT_GT(short_arcs, 1000);
  EXPECT_GT(long_arcs, 1000);
  std::printf("R arcs: worst centre error %.2f units of 0.1 um\n", worst * 1e4);
}

TEST(GcodeArcs, IllConditionedRArcsStayOnTheCircle) {
  // A 1 um chord on a 100 mm radius: the centre is far from the chord, and
  // the normalised square roots keep it on both circles to within 0.5 um.
  for (const char* line : {"G2 X0.001 Y0 R100", "G3 X0 Y0.0007 R-100", "G2 X0.0003 Y0.0004 R50"}) {
    Interp g(kAxes);
    const Action a = ok(g, std::string("F10 ") + line);
    const double ux = a.centre_length[0] / 1e4, uy = a.centre_length[1] / 1e4;
    double ex = 0, ey = 0, r = 0;
    std::sscanf(line + 3, "X%lf Y%lf R%lf", &ex, &ey, &r);
    EXPECT_NEAR(std::hypot(ux, uy), std::fabs(r), 5e-5) << line;
    EXPECT_NEAR(std::hypot(ex - ux, ey - uy), std::fabs(r), 5e-5) << line;
    double cx, cy;
    reference_centre(0, 0, ex, ey, r, line[1] == '2', cx, cy);
    EXPECT_NEAR(ux, cx, 5e-4) << line;  // sensitive to the end's 0.1 um rounding
    EXPECT_NEAR(uy, cy, 5e-4) << line;
  }
}

TEST(GcodeArcs, FullCirclesWithOffsets) {
  Interp g(kAxes);
  ok(g, "G0 X10 Y20");
  Action a = ok(g, "G2 X10 Y20 I5 J0 F300");
  ASSERT_EQ(a.kind, GcodeActionKind::arc);
  EXPECT_TRUE(a.clockwise);
  EXPECT_EQ(a.target[0], 800);
  EXPECT_EQ(a.target[1], 2000);
  EXPECT_EQ(a.centre_length[0], 50000);
  EXPECT_EQ(a.centre_length[1], 0);
  EXPECT_EQ(a.centre[0], 400);
  EXPECT_EQ(a.radius, 50000);
  // Only one axis word is needed; the other stays where it is.
  a = ok(g, "G3 X10 I-3 J-4");
  EXPECT_FALSE(a.clockwise);
  EXPECT_EQ(a.radius, 50000);
  EXPECT_EQ(a.centre[0], -240);
  EXPECT_EQ(a.centre[1], -400);
  // An R arc cannot be a full circle.
  Action b;
  EXPECT_EQ(g.run("G2 X10 Y20 R5", b), GcodeError::arc_full_circle_r);
}

TEST(GcodeArcs, EndPointTolerance) {
  // Centre at +r on X from the origin, end on the far side at 2r + delta:
  // radius mismatch exactly delta.
  struct Case {
    double r, delta;
    bool accepted;
  } cases[] = {{1, 0.0049, true},   {1, 0.0051, false},   {1, -0.005, true},   {1, -0.0051, false},
               {100, 0.099, true},  {100, 0.101, false},  {100, -0.1, true},   {1000, 0.499, true},
               {1000, 0.501, false}, {1000, -0.5, true},  {1000, -0.5001, false}};
  for (const Case& c : cases) {
    Interp g(kAxes);
    const std::string line = fmt("G2 X%.4f I%.4f F100", 2 * c.r + c.delta, c.r);
    Action a;
    EXPECT_EQ(g.run(line.c_str(), a), c.accepted ? GcodeError::none : GcodeError::arc_radius_mismatch) << line;
    // Same at 90 degrees (end on the Y axis through the centre).
    const std::string line2 = fmt("G3 X%.4f Y%.4f I%.4f F100", c.r, c.r + c.delta, c.r);
    Interp h(kAxes);
    EXPECT_EQ(h.run(line2.c_str(), a), c.accepted ? GcodeError::none : GcodeError::arc_radius_mismatch) << line2;
  }
}

TEST(GcodeArcs, RSlightlyTooShortIsAHalfCircle) {
  Interp g(kAxes);
  Action a = ok(g, "G2 X10 R4.996 F100");  // 10 mm chord, 2R 8 um short: within 2 x 5 um
  EXPECT_EQ(a.centre_length[0], 50000);
  EXPECT_EQ(a.centre_length[1], 0);
  EXPECT_EQ(a.radius, 50000);
  Interp h(kAxes);
  EXPECT_EQ(h.run("G2 X10 R4.994 F100", a), GcodeError::arc_radius_too_small);
  // Exactly half: the centre is the chord's middle, either direction.
  for (const char* line : {"G2 X10 R5 F100", "G3 X10 R-5 F100", "G2 X0 Y-10 R5 F100"}) {
    Interp k(kAxes);
    a = ok(k, line);
    const bool on_y = line[4] == '0';
    EXPECT_EQ(a.centre_length[0], on_y ? 0 : 50000) << line;
    EXPECT_EQ(a.centre_length[1], on_y ? -50000 : 0) << line;
  }
}

TEST(GcodeArcs, OtherPlanes) {
  // G18: first axis Z, second X (offsets K, I), normal Y; G19: Y, Z (J, K), X.
  // Counter-clockwise is from the first axis towards the second.
  struct Case {
    const char* line;
    uint8_t first, second, normal;
    int32_t o0, o1;
  } cases[] = {
      {"G18 G2 X5 Z5 R5", 2, 0, 1, 50000, 0},   // from (Z0,X0) to (Z5,X5): cw round (Z5,X0)
      {"G18 G3 X5 Z5 R5", 2, 0, 1, 0, 50000},
      {"G18 G2 X10 K0 I5", 2, 0, 1, 0, 50000},  // offsets: K for Z, I for X
      {"G19 G2 Y5 Z5 R5", 1, 2, 0, 50000, 0},   // from (Y0,Z0) to (Y5,Z5): cw round (Y5,Z0)
      {"G19 G3 Y5 Z5 R5", 1, 2, 0, 0, 50000},
      {"G19 G3 Y10 J5 K0", 1, 2, 0, 50000, 0},
  };
  for (const Case& c : cases) {
    Interp g(kAxes);
    const Action a = ok(g, std::string("F100 ") + c.line);
    ASSERT_EQ(a.kind, GcodeActionKind::arc) << c.line;
    EXPECT_EQ(a.plane_axis[0], c.first) << c.line;
    EXPECT_EQ(a.plane_axis[1], c.second) << c.line;
    EXPECT_EQ(a.plane_axis[2], c.normal) << c.line;
    EXPECT_EQ(a.centre_length[0], c.o0) << c.line;
    EXPECT_EQ(a.centre_length[1], c.o1) << c.line;
  }
  // The reference geometry in the G18 plane, random.
  std::mt19937 rng(18);
  for (int n = 0; n < 500; ++n) {
    Interp g(kAxes);
    const double ez = int(rng() % 200001 - 100000) / 1e3, ex = int(rng() % 200001 - 100000) / 1e3;
    if (std::hypot(ez, ex) < 1) continue;
    const double r = std::round(std::hypot(ez, ex) / 2 * 1.5 * 1e4) / 1e4 * (rng() % 2 ? 1 : -1);
    const bool cw = rng() % 2;
    const std::string line = fmt(cw ? "G18 G2 X%.4f Z%.4f R%.4f F9" : "G18 G3 X%.4f Z%.4f R%.4f F9", ex, ez, r);
    const Action a = ok(g, line);
    double cz, cx;
    reference_centre(0, 0, ez, ex, r, cw, cz, cx);
    EXPECT_NEAR(a.centre_length[0] / 1e4, cz, 1e-4) << line;
    EXPECT_NEAR(a.centre_length[1] / 1e4, cx, 1e-4) << line;
  }
  // Words of another plane are not used.
  Interp g(kAxes);
  Action a;
  EXPECT_EQ(g.run("G18 G2 X10 J5 F100", a), GcodeError::missing_arc_words);
  EXPECT_EQ(g.run("G19 G2 Y10 I5 J5 F100", a), GcodeError::unused_word);
}

TEST(GcodeArcs, HelixAndExtrusionMoveLinearly) {
  Interp g(kAxes);
  const Action a = ok(g, "G2 X10 Y0 I5 Z-2 E3 F100");
  EXPECT_EQ(a.kind, GcodeActionKind::arc);
  EXPECT_EQ(a.target[2], -800);
  EXPECT_EQ(a.target[3], 279);
  EXPECT_EQ(a.axes, 0xF);
}

TEST(GcodeArcs, InchesIncrementalAndOffsets) {
  Interp g(kAxes);
  Action a = ok(g, "G20 G2 X1 Y1 I1 J0 F10");  // quarter circle, 1 in radius
  EXPECT_EQ(a.centre_length[0], 254000);
  EXPECT_EQ(a.radius, 254000);
  EXPECT_EQ(a.target[0], 2032);
  // Offsets are relative to the start whatever G90/G91 say.
  ok(g, "G21 G90 G0 X10 Y20");
  a = ok(g, "G91 G2 X10 Y0 I5 J0");
  EXPECT_EQ(a.target[0], 1600);
  EXPECT_EQ(a.centre_length[0], 50000);
  // With a G92 offset the centre in steps is still start-relative.
  ok(g, "G90 G92 X0 Y0");
  a = ok(g, "G3 X-6 Y0 R3");
  EXPECT_EQ(a.target[0], 1600 - 480);
  EXPECT_EQ(a.centre[0], -240);
  EXPECT_EQ(a.centre[1], 0);
}

TEST(GcodeArcs, GeometryBeyondTheRangeIsRefused) {
  Interp g(kAxes);
  ok(g, "G0 X-200000");
  Action a;
  // The chord, 400 m, leaves the int32 range of 0.1 um.
  EXPECT_EQ(g.run("G2 X200000 R200000 F1", a), GcodeError::target_out_of_range);
  // A centre beyond the coordinate range.
  EXPECT_EQ(g.run("G2 X-199990 I-20000 F1", a), GcodeError::arc_radius_mismatch);
  EXPECT_EQ(g.run("G2 X-200000 Y0.001 I-20000 F1", a), GcodeError::target_out_of_range);
  EXPECT_EQ(g.state().axis[0].coord, -2000000000);
}
