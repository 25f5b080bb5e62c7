// ArcDda (core/motion/arc_dda.h) against geometry computed here in floating
// point: seed-002 §4's vectors with its one-step end-point defect fixed,
// sweeps of radii, centres, start angles, directions and sweeps with end
// points rounded to steps, exhaustive full circles of small radii, radii near
// the coordinate limit, helical ride-along, the path length and the R form.
// This file: the seed vectors, the R form, planning and its refusals, the
// other planes and the helix; the sweeps, limits and mismatches:
// test_motion_arc_sweep.cpp; the geometry: arc_check.h.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "core/motion/arc_dda.h"
#include "core/motion/line_dda.h"

#include "arc_check.h"

namespace {

using namespace arctest;


// seed-002 §4's vectors. The seed's DDA runs a fixed number of iterations
// (the arc length in BLU) and lands where its integration lands; ours ends on
// the end point by construction.
TEST(MotionArcSeedVectors, EndsExactlyWhereTheSeedMissesByOneStep) {
  struct Vector {
    Arc arc;
    int seed_iterations;
    int seed_x, seed_y;  // where the printed seed algorithm ends
  };
  const Vector vectors[] = {
      {{-100, 100, -100, 0, ArcDir::ccw}, 157, -100, 100},      // G03 X-100 Y100 I-100 J0
      {{-100, -100, -100, 0, ArcDir::cw}, 157, -100, -100},     // G02 X-100 Y-100 I-100 J0
      {{1000, -1000, 0, -1000, ArcDir::cw}, 1571, 1001, -999},  // G02 X1000 Y-1000 I0 J-1000
      {{-200, 0, -100, 0, ArcDir::ccw}, 314, -200, 1},          // G03 X-200 Y0 I-100 J0
  };
  for (const Vector& v : vectors) {
    const ArcRun r = run(v.arc);
    ASSERT_EQ(r.err, ArcError::none);
    ASSERT_FALSE(r.xs.empty());
    EXPECT_EQ(r.xs.back(), v.arc.ex);
    EXPECT_EQ(r.ys.back(), v.arc.ey);
    // The seed's iteration count is the arc length: ours reports it too.
    EXPECT_NEAR(r.length_q8 / 256.0, v.seed_iterations, 0.5);
    const Measured m = check_arc(v.arc, "seed vector");
    EXPECT_LT(m.max_dev, 0.5L);
  }
  // Event counts: one per step of the faster axis, sqrt(2) R per quarter
  // (100 sqrt 2 = 141.4, 1000 sqrt 2 = 1414.2): 141, 141, 1414, 282.
  EXPECT_EQ(run(vectors[0].arc).planned, 141u);
  EXPECT_EQ(run(vectors[1].arc).planned, 141u);
  EXPECT_EQ(run(vectors[2].arc).planned, 1414u);
  EXPECT_EQ(run(vectors[3].arc).planned, 282u);
}

TEST(MotionArcSeedVectors, RadiusFormPicksTheCentre) {
  int32_t i = 99, j = 99;
  // X10 Y0 R5: the half circle's centre is the chord's midpoint.
  ASSERT_EQ(am::arc_centre_from_radius(10, 0, 5, ArcDir::cw, &i, &j), ArcError::none);
  EXPECT_EQ(i, 5);
  EXPECT_EQ(j, 0);
  ASSERT_EQ(am::arc_centre_from_radius(10, 0, 5, ArcDir::ccw, &i, &j), ArcError::none);
  EXPECT_EQ(i, 5);
  EXPECT_EQ(j, 0);
  // X10 Y10 R10: (10, 0) or (0, 10); positive R is the shorter arc, so G02
  // turns around (10, 0) and G03 around (0, 10); negative R swaps them.
  ASSERT_EQ(am::arc_centre_from_radius(10, 10, 10, ArcDir::cw, &i, &j), ArcError::none);
  EXPECT_EQ(i, 10);
  EXPECT_EQ(j, 0);
  ASSERT_EQ(am::arc_centre_from_radius(10, 10, 10, ArcDir::ccw, &i, &j), ArcError::none);
  EXPECT_EQ(i, 0);
  EXPECT_EQ(j, 10);
  ASSERT_EQ(am::arc_centre_from_radius(10, 10, -10, ArcDir::cw, &i, &j), ArcError::none);
  EXPECT_EQ(i, 0);
  EXPECT_EQ(j, 10);
  // Too short for the chord, and the full circle, have no centre.
  EXPECT_EQ(am::arc_centre_from_radius(10, 10, 5, ArcDir::cw, &i, &j), ArcError::bad_radius);
  EXPECT_EQ(am::arc_centre_from_radius(0, 0, 5, ArcDir::cw, &i, &j), ArcError::bad_radius);
  EXPECT_EQ(am::arc_centre_from_radius(10, 0, 0, ArcDir::cw, &i, &j), ArcError::bad_radius);
  // Half a step short of the chord (its rounding) is taken as a half circle.
  ASSERT_EQ(am::arc_centre_from_radius(11, 0, 5, ArcDir::cw, &i, &j), ArcError::none);
  EXPECT_EQ(j, 0);
}

TEST(MotionArcRadiusForm, CentreIsTheExactOneRoundedAndTheArcHasTheRightSide) {
  std::mt19937_64 rng(5);
  int checked = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const int32_t span = trial < 10000 ? 300 : 3000000;
    const int32_t x = int32_t(rng() % (2 * span + 1)) - span, y = int32_t(rng() % (2 * span + 1)) - span;
    const long double d = hypotl(x, y);
    if (d == 0) continue;
    const int32_t r_abs = int32_t(ceill(d / 2) + rng() % (uint64_t(span) + 1));
    const int32_t r = (rng() & 1) ? r_abs : -r_abs;
    const ArcDir dir = (rng() & 1) ? ArcDir::ccw : ArcDir::cw;
    int32_t i, j;
    ASSERT_EQ(am::arc_centre_from_radius(x, y, r, dir, &i, &j), ArcError::none);
    // Reference: midpoint + t (-y, x), t = s sqrt(r^2 - d^2/4) / d.
    const long double s = (dir == ArcDir::ccw ? 1 : -1) * (r > 0 ? 1 : -1);
    const long double h = sqrtl(std::max(0.0L, (long double)r_abs * r_abs - d * d / 4));
    const long double ci = x / 2.0L - s * h / d * y, cj = y / 2.0L + s * h / d * x;
    const long double fi = ci - floorl(ci), fj = cj - floorl(cj);
    if (fabsl(fi - 0.5L) < 1e-6L || fabsl(fj - 0.5L) < 1e-6L) continue;  // a tie either way
    EXPECT_EQ(i, int32_t(floorl(ci + 0.5L))) << x << " " << y << " r " << r;
    EXPECT_EQ(j, int32_t(floorl(cj + 0.5L))) << x << " " << y << " r " << r;
    // Positive R sweeps at most half a turn, negative at least half.
    long double swept = angle_of(x - ci, y - cj) - angle_of(-ci, -cj);
    if (dir == ArcDir::cw) swept = -swept;
    while (swept < 0) swept += 2 * kPi;
    if (r > 0) {
      EXPECT_LE(swept, kPi + 1e-9L);
    } else {
      EXPECT_GE(swept, kPi - 1e-9L);
    }
    ++checked;
  }
  EXPECT_GT(checked, 19000);
}

TEST(MotionArcPlanning, RejectsWhatItCannotDo) {
  ArcDda dda;
  EXPECT_EQ(dda.start(10, 10, 0, 0, ArcDir::cw), ArcError::zero_radius);   // centre on the start
  EXPECT_EQ(dda.start(10, 10, 10, 10, ArcDir::cw), ArcError::zero_radius);  // end on the centre
  EXPECT_TRUE(dda.finished());
  EXPECT_EQ(dda.events(), 0u);
  EXPECT_EQ(dda.start(0, 0, ArcDda::kMaxCoord + 1, 0, ArcDir::cw), ArcError::out_of_range);
  EXPECT_EQ(dda.start(0, 0, ArcDda::kMaxCoord, 0, ArcDir::cw), ArcError::none);
  EXPECT_EQ(dda.start(0, 0, 5000, 0, ArcDir::cw, 0, 1), ArcError::none);
  // Radius mismatch limit: |r_end^2 - r_start^2| <= 2^29.
  EXPECT_EQ(dda.start(40000, 0, 1, 0, ArcDir::ccw), ArcError::out_of_range);
}

TEST(MotionArcHelix, LinearAxesRideAlongAsMinorsOfTheArcEvents) {
  // Z and E move in proportion to the arc's events: a LineDda over
  // events() events, stepped once per arc event.
  const Arc a{-713, 699, -713, 0, ArcDir::ccw};  // a quarter of radius 713 to (0, 699): a spiral
  ArcDda arc;
  ASSERT_EQ(arc.start(a.ex, a.ey, a.i, a.j, a.dir), ArcError::none);
  am::LineDda<2> minors;
  const int32_t ze[2] = {-250, 391};
  ASSERT_TRUE(minors.start(ze, arc.events(), am::DdaPhase::nearest));
  int64_t x = 0, y = 0, z = 0, e = 0;
  uint32_t k = 0;
  const uint32_t n = arc.events();
  while (!arc.finished()) {
    ASSERT_FALSE(minors.finished());
    const StepEvent xy = arc.next(), m = minors.next();
    const uint8_t axes = uint8_t(xy.axes | (m.axes << 2));  // X Y Z E in bits 0..3
    const uint8_t dirs = uint8_t(xy.dirs | (m.dirs << 2));
    ++k;
    if (axes & 1) x += (dirs & 1) ? 1 : -1;
    if (axes & 2) y += (dirs & 2) ? 1 : -1;
    if (axes & 4) z += (dirs & 4) ? 1 : -1;
    if (axes & 8) e += (dirs & 8) ? 1 : -1;
    // Each linear axis within half a step of its share of the events.
    ASSERT_LE(fabsl(fabsl((long double)z) - 250.0L * k / n), 0.5L);
    ASSERT_LE(fabsl(fabsl((long double)e) - 391.0L * k / n), 0.5L);
  }
  EXPECT_TRUE(minors.finished());
  EXPECT_EQ(x, a.ex);
  EXPECT_EQ(y, a.ey);
  EXPECT_EQ(z, -250);
  EXPECT_EQ(e, 391);
}

TEST(MotionArcPlanning, OtherPlanesMapTheEventBits) {
  // G18-style: the arc's first axis on bit 2, second on bit 0.
  ArcDda dda;
  ASSERT_EQ(dda.start(-100, 100, -100, 0, ArcDir::ccw, 2, 0), ArcError::none);
  int64_t a = 0, b = 0;
  while (!dda.finished()) {
    const StepEvent ev = dda.next();
    ASSERT_EQ(ev.axes & ~0b101, 0);
    if (ev.axes & 4) a += (ev.dirs & 4) ? 1 : -1;
    if (ev.axes & 1) b += (ev.dirs & 1) ? 1 : -1;
  }
  EXPECT_EQ(a, -100);
  EXPECT_EQ(b, 100);
}

}  // namespace
