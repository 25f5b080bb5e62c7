// What the ArcDda tests share (test_motion_arc.cpp,
// test_motion_arc_sweep.cpp): an arc run event by event into its points,
// and the geometry computed here in floating point that every point, the
// count and the path length are checked against.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/motion/arc_dda.h"

namespace arctest {

using am::ArcDda;
using am::ArcDir;
using am::ArcError;
using am::StepEvent;

constexpr long double kPi = 3.141592653589793238462643383279502884L;

// Angle of (x, y) in [0, 2 pi).
inline long double angle_of(long double x, long double y) {
  long double a = atan2l(y, x);
  return a < 0 ? a + 2 * kPi : a;
}

struct Arc {
  int32_t ex, ey, i, j;  // end and centre offset from the start, steps
  ArcDir dir;
};

struct ArcRun {
  ArcError err = ArcError::none;
  uint32_t planned = 0;     // events() before the first event
  uint32_t diagonals = 0;   // diagonal_events()
  uint64_t length_q8 = 0;
  std::vector<int64_t> xs, ys;  // every point after each event, relative to the start
  std::vector<uint8_t> axes, dirs;
  bool accessors_agree = true;  // x(), y(), remaining() along the run
};

inline ArcRun run(const Arc& a) {
  ArcRun r;
  ArcDda dda;
  r.err = dda.start(a.ex, a.ey, a.i, a.j, a.dir);
  if (r.err != ArcError::none) return r;
  r.planned = dda.events();
  r.diagonals = dda.diagonal_events();
  r.length_q8 = dda.path_length_q8();
  int64_t x = 0, y = 0;
  uint32_t left = r.planned;
  while (!dda.finished()) {
    if (dda.remaining() != left) r.accessors_agree = false;
    const StepEvent ev = dda.next();
    --left;
    r.axes.push_back(ev.axes);
    r.dirs.push_back(ev.dirs);
    if (ev.axes & 1) x += (ev.dirs & 1) ? 1 : -1;
    if (ev.axes & 2) y += (ev.dirs & 2) ? 1 : -1;
    r.xs.push_back(x);
    r.ys.push_back(y);
    if (dda.x() != x || dda.y() != y) r.accessors_agree = false;
    if (r.xs.size() > 4 * size_t(r.planned) + 16) break;  // runaway guard
  }
  return r;
}

// The checks every arc must pass. Returns the largest |distance to the centre
// - start radius| over the path (steps).
struct Measured {
  long double max_dev = 0;  // from the start circle
  long double max_band_excess = 0;  // beyond the [start, end] radius band
};

inline Measured check_arc(const Arc& a, const char* what) {
  SCOPED_TRACE(what);
  Measured m;
  const ArcRun r = run(a);
  EXPECT_EQ(r.err, ArcError::none);
  if (r.err != ArcError::none) return m;
  const long double cx = a.i, cy = a.j;
  const long double r0 = hypotl(cx, cy), re = hypotl(a.ex - cx, a.ey - cy);
  // 1. The planned count is the run's count, and the run ends exactly on the
  //    end point, reached there for the first time (a full circle returns to
  //    the start only at the end).
  EXPECT_EQ(r.xs.size(), size_t(r.planned));
  EXPECT_TRUE(r.accessors_agree);
  if (r.xs.empty()) return m;
  EXPECT_EQ(r.xs.back(), a.ex);
  EXPECT_EQ(r.ys.back(), a.ey);
  for (size_t k = 0; k + 1 < r.xs.size(); ++k)
    if (r.xs[k] == a.ex && r.ys[k] == a.ey) {
      ADD_FAILURE() << "end point reached early at event " << k + 1 << " of " << r.xs.size();
      break;
    }
  // 2. Every event is a king move: one step on X, Y or both, never nothing.
  uint32_t diagonals = 0;
  for (uint8_t axes : r.axes) {
    EXPECT_TRUE(axes == 1 || axes == 2 || axes == 3) << int(axes);
    diagonals += axes == 3;
  }
  EXPECT_EQ(diagonals, r.diagonals);
  // 3. Distance from the centre (the start radius, and the band between the
  //    start and end radius).
  const long double lo = std::min(r0, re), hi = std::max(r0, re);
  for (size_t k = 0; k < r.xs.size(); ++k) {
    const long double d = hypotl(r.xs[k] - cx, r.ys[k] - cy);
    m.max_dev = std::max(m.max_dev, fabsl(d - r0));
    m.max_band_excess = std::max(m.max_band_excess, d < lo ? lo - d : (d > hi ? d - hi : 0));
  }
  // 4. No needless reversal: an axis moves the way the circle's tangent goes
  //    (CCW: dx ~ -y, dy ~ x relative to the centre), except within one step
  //    of where that component changes sign.
  const long double sense = a.dir == ArcDir::ccw ? 1 : -1;
  int64_t px = 0, py = 0;
  for (size_t k = 0; k < r.xs.size(); ++k) {
    const long double rx = px - cx, ry = py - cy;  // the point the step leaves
    if ((r.axes[k] & 1) && fabsl(ry) > 1) {
      const bool forward = r.dirs[k] & 1;
      EXPECT_EQ(forward, -sense * ry > 0) << "x step " << k + 1 << " at (" << rx << "," << ry << ")";
    }
    if ((r.axes[k] & 2) && fabsl(rx) > 1) {
      const bool forward = r.dirs[k] & 2;
      EXPECT_EQ(forward, sense * rx > 0) << "y step " << k + 1 << " at (" << rx << "," << ry << ")";
    }
    px = r.xs[k];
    py = r.ys[k];
  }
  // 5. The path length is the programmed arc's: mean radius times the swept
  //    angle (same direction, (0, 2 pi]).
  long double swept = angle_of(a.ex - cx, a.ey - cy) - angle_of(-cx, -cy);
  if (a.dir == ArcDir::cw) swept = -swept;
  while (swept <= 0) swept += 2 * kPi;
  if (a.ex == 0 && a.ey == 0) swept = 2 * kPi;
  const long double along = (r0 + re) / 2 * swept, radial = re - r0;
  // (radii in Q8: up to 1/256 step each, times the angle; the angles in
  // Q31 radians: a few 2^-31 each, times the radius)
  EXPECT_NEAR(r.length_q8 / 256.0L, sqrtl(along * along + radial * radial), 0.05L + r0 * 4e-9L);
  return m;
}

inline bool on_start_circle(const Arc& a) {
  const int64_t ux = int64_t(a.ex) - a.i, uy = int64_t(a.ey) - a.j;
  return ux * ux + uy * uy == int64_t(a.i) * a.i + int64_t(a.j) * a.j;
}

}  // namespace arctest
