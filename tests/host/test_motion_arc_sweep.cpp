// ArcDda (core/motion/arc_dda.h) swept against geometry computed here in
// floating point: radii 1 to 5000 with end points rounded to steps, every
// full circle of small radii, cw against ccw, radii near the coordinate
// limit across diagonals and axes, and spirals (end points off the start
// circle) within the radius band. The rest: test_motion_arc.cpp; the
// geometry: arc_check.h.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "arc_check.h"
#include "core/motion/arc_dda.h"

namespace {

using namespace arctest;

// Rounded end point of an arc from the start (0, 0) around the centre offset
// (i, j), swept by `sweep` radians in `dir`.
Arc rounded_arc(int32_t i, int32_t j, long double sweep, ArcDir dir) {
  const long double r0 = hypotl(i, j), a0 = angle_of(-i, -j);
  const long double ae = a0 + (dir == ArcDir::ccw ? sweep : -sweep);
  Arc a{int32_t(lroundl(i + r0 * cosl(ae))), int32_t(lroundl(j + r0 * sinl(ae))), i, j, dir};
  if (sweep >= 2 * kPi - 1e-12L) a.ex = a.ey = 0;
  return a;
}

TEST(MotionArcSweep, RadiiOneToFiveThousandRoundedEndPoints) {
  std::mt19937_64 rng(42);
  const long double sweeps[] = {kPi / 2, kPi, 1.25L * kPi, 1.5L * kPi, 2 * kPi};
  long double worst_exact = 0, worst_rounded = 0, worst_excess = 0;
  int arcs = 0, on_circle = 0;
  // Every radius 1..200 forty times (quarter, half, over-half, three
  // quarters, full, or a random sweep); every radius 201..5000 once with a
  // sweep up to 40 degrees; 600 long arcs of random radii up to 5000.
  const int small = 200 * 40, every = 4800, large = 600;
  for (int trial = 0; trial < small + every + large; ++trial) {
    int32_t radius;
    long double sweep;
    if (trial < small) {
      radius = 1 + trial % 200;
      sweep = trial % 3 ? sweeps[rng() % 5] : (rng() % 1000000 + 1) / 1e6L * 2 * kPi;
    } else if (trial < small + every) {
      radius = 201 + (trial - small);
      sweep = (rng() % 1000000 + 1) / 1e6L * (40 * kPi / 180);
    } else {
      radius = 1 + int32_t(rng() % 5000);
      sweep = sweeps[rng() % 5];
    }
    const long double a0 = (rng() % 1000000) / 1e6L * 2 * kPi;
    const int32_t i = -int32_t(lroundl(radius * cosl(a0))), j = -int32_t(lroundl(radius * sinl(a0)));
    if (i == 0 && j == 0) continue;
    const ArcDir dir = (rng() & 1) ? ArcDir::ccw : ArcDir::cw;
    const Arc a = rounded_arc(i, j, sweep, dir);
    if (a.ex == i && a.ey == j) continue;
    const Measured m = check_arc(a, "sweep");
    if (::testing::Test::HasFailure()) {
      ADD_FAILURE() << "arc i " << i << " j " << j << " end " << a.ex << "," << a.ey << " "
                    << (dir == ArcDir::cw ? "cw" : "ccw");
      return;
    }
    ++arcs;
    const long double r0 = hypotl(i, j), re = hypotl(a.ex - i, a.ey - j);
    if (on_start_circle(a)) {
      ++on_circle;
      worst_exact = std::max(worst_exact, m.max_dev);
    } else {
      worst_rounded = std::max(worst_rounded, m.max_dev);
      // Off the circle by its rounding only: within half a step of the band.
      EXPECT_LE(m.max_dev, 0.5L + fabsl(re - r0)) << i << " " << j << " " << a.ex << " " << a.ey;
    }
    worst_excess = std::max(worst_excess, m.max_band_excess);
  }
  EXPECT_GT(arcs, 13000);
  EXPECT_GT(on_circle, 1000);
  EXPECT_LT(worst_exact, 0.5L);   // on the start circle: every point within half a step
  EXPECT_LT(worst_rounded, 1.0L);  // rounded end: within one step (measured 0.85)
  EXPECT_LT(worst_excess, 0.5L);
  RecordProperty("worst_on_circle", std::to_string(double(worst_exact)));
  RecordProperty("worst_rounded_end", std::to_string(double(worst_rounded)));
}

TEST(MotionArcSweep, EveryFullCircleOfSmallRadiiClosesWithinHalfAStep) {
  // Every lattice start point with radius <= 60, both directions.
  long double worst = 0;
  int circles = 0;
  for (int32_t i = -60; i <= 60; ++i)
    for (int32_t j = -60; j <= 60; ++j) {
      if ((i == 0 && j == 0) || i * i + j * j > 3600) continue;
      for (ArcDir dir : {ArcDir::ccw, ArcDir::cw}) {
        const ArcRun r = run(Arc{0, 0, i, j, dir});
        ASSERT_EQ(r.err, ArcError::none);
        ASSERT_EQ(r.xs.size(), size_t(r.planned));
        ASSERT_EQ(r.xs.back(), 0);
        ASSERT_EQ(r.ys.back(), 0);
        const long double r0 = hypotl(i, j);
        for (size_t k = 0; k < r.xs.size(); ++k) {
          worst = std::max(worst, fabsl(hypotl(r.xs[k] - i, r.ys[k] - j) - r0));
          ASSERT_FALSE(k + 1 < r.xs.size() && r.xs[k] == 0 && r.ys[k] == 0) << i << " " << j;
        }
        ++circles;
      }
    }
  EXPECT_GT(circles, 22000);
  EXPECT_LT(worst, 0.5L);
}

TEST(MotionArcSweep, CountIsSymmetricAndCwMirrorsCcw) {
  // A clockwise arc is the counter-clockwise arc mirrored in y: same count,
  // mirrored points.
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 300; ++trial) {
    const int32_t i = int32_t(rng() % 801) - 400, j = int32_t(rng() % 801) - 400;
    if (i == 0 && j == 0) continue;
    const Arc ccw = rounded_arc(i, j, (rng() % 1000 + 1) / 1000.0L * 2 * kPi, ArcDir::ccw);
    const Arc cw{ccw.ex, -ccw.ey, ccw.i, -ccw.j, ArcDir::cw};
    const ArcRun a = run(ccw), b = run(cw);
    ASSERT_EQ(a.err, ArcError::none);
    ASSERT_EQ(b.err, ArcError::none);
    ASSERT_EQ(a.planned, b.planned);
    for (size_t k = 0; k < a.xs.size(); ++k) {
      ASSERT_EQ(a.xs[k], b.xs[k]);
      ASSERT_EQ(a.ys[k], -b.ys[k]);
    }
  }
}

TEST(MotionArcLimits, LargeRadiiAcrossDiagonalsAndAxes) {
  // Short arcs of radii up to 2^28 - 1 through the places where the fast
  // axis changes (diagonals) and the quadrant changes (axes).
  std::mt19937_64 rng(3);
  long double worst = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const int64_t radius = (int64_t(1) << 20) + int64_t(rng() % ((int64_t(1) << 28) - (int64_t(1) << 21)));
    const long double through = (trial % 8) * kPi / 4;  // an axis or a diagonal
    const long double span = 20000.0L / radius;         // about 20000 steps of arc
    const ArcDir dir = trial % 2 ? ArcDir::ccw : ArcDir::cw;
    const long double a0 = dir == ArcDir::ccw ? through - span / 2 : through + span / 2;
    const int32_t i = -int32_t(lroundl(radius * cosl(a0))), j = -int32_t(lroundl(radius * sinl(a0)));
    const Arc a = rounded_arc(i, j, span, dir);
    const Measured m = check_arc(a, "large radius");
    if (::testing::Test::HasFailure()) return;
    if (on_start_circle(a)) {
      EXPECT_LT(m.max_dev, 0.5L);
    }
    worst = std::max(worst, m.max_band_excess);
  }
  EXPECT_LT(worst, 0.5L);
}

TEST(MotionArcMismatch, SpiralsLandExactlyWithinTheRadiusBand) {
  // End points off the start circle by more than rounding (G-code radius
  // tolerances): the path blends the radius, or finishes with a straight
  // tail when the arc is too short for that, and still ends on the end.
  std::mt19937_64 rng(8);
  long double worst = 0;
  for (int trial = 0; trial < 6000; ++trial) {
    const long double delta = 0.75L + (trial % 5);  // 0.75 .. 4.75 steps
    const int32_t radius = 5 + int32_t(rng() % 3000);
    const long double a0 = (rng() % 1000000) / 1e6L * 2 * kPi;
    const int32_t i = -int32_t(lroundl(radius * cosl(a0))), j = -int32_t(lroundl(radius * sinl(a0)));
    const long double r0 = hypotl(i, j), sweep = (rng() % 1000000 + 1) / 1e6L * 2 * kPi;
    const ArcDir dir = (rng() & 1) ? ArcDir::ccw : ArcDir::cw;
    const long double re = r0 + ((rng() & 1) ? delta : -delta);
    const long double ae = angle_of(-i, -j) + (dir == ArcDir::ccw ? sweep : -sweep);
    const Arc a{int32_t(lroundl(i + re * cosl(ae))), int32_t(lroundl(j + re * sinl(ae))), i, j, dir};
    if (a.ex == i && a.ey == j) continue;
    const ArcRun r = run(a);
    ASSERT_EQ(r.err, ArcError::none) << i << " " << j << " " << a.ex << " " << a.ey;
    ASSERT_EQ(r.xs.size(), size_t(r.planned));
    ASSERT_EQ(r.xs.back(), a.ex);
    ASSERT_EQ(r.ys.back(), a.ey);
    const long double rea = hypotl(a.ex - i, a.ey - j), lo = std::min(r0, rea), hi = std::max(r0, rea);
    for (size_t k = 0; k < r.xs.size(); ++k) {
      ASSERT_TRUE(r.axes[k] == 1 || r.axes[k] == 2 || r.axes[k] == 3);
      const long double d = hypotl(r.xs[k] - i, r.ys[k] - j);
      worst = std::max(worst, d < lo ? lo - d : (d > hi ? d - hi : 0));
    }
  }
  EXPECT_LT(worst, 1.0L);  // measured 0.83
  RecordProperty("worst_band_excess", std::to_string(double(worst)));
}


}  // namespace
