// PathPlanner (core/motion/path_planner.h) junctions and polylines.
//   - The junction speed against grbl's formula, in double, from the very
//     float distances the planner gets: v^2 = a d h / (1 - h), h = sin(theta
//     / 2), a = min_i a_i / |j_i| over the unit change of direction j; theta
//     over 0..180 degrees, planes of every orientation, unequal axis
//     accelerations, three deviations; blocks long enough that only the
//     junction limits the speed. Within 0.05 % of v^2 from 0.05 degrees of
//     deflection (theta 179.95) to an exact reversal (theta 0: v = 0). (At
//     0.01 degrees the float directions give 0.08 %; there the formula
//     allows 51 m/s at 1000 mm/s^2 and 0.01 mm, and the nominal speed rules.)
//   - The cap: both blocks' nominal speeds; straight on = the nominal.
//   - Polylines through a 16-block ring, the oldest block taken whenever the
//     ring is full: a 300-segment circle of 0.1 mm chords, a zig-zag of 90
//     degree corners, collinear segments of varied lengths. Their vertices are
//     not stops; the last block of each ends at 0.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "core/motion/path_planner.h"

namespace {

constexpr double kPi = 3.14159265358979323846;

// X, Y, Z with unequal scales and accelerations; rates high enough that the
// junction rules (the sweep), or the feed (the polylines).
const am::PathAxis kFast[3] = {{80, 4e8f, 80000, true}, {100, 5e8f, 50000, true}, {400, 1e9f, 40000, true}};
const am::PathAxis kAxes[3] = {{80, 16000, 80000, true}, {100, 20000, 50000, true}, {400, 4000, 40000, true}};

using Pair4 = am::PathPlanner<3, 4>;
using Ring16 = am::PathPlanner<3, 16>;

struct Move {
  int32_t steps[3];
  float mm[3];
};

Move move_along(const double (&dir)[3], double length, const am::PathAxis (&axes)[3]) {
  Move m{};
  for (int i = 0; i < 3; ++i) {
    m.mm[i] = float(dir[i] * length);
    m.steps[i] = int32_t(std::llround(double(m.mm[i]) * axes[i].steps_per_mm));
  }
  return m;
}

double norm(const double (&v)[3]) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

void unit_of(const Move& m, double (&u)[3]) {
  const double v[3] = {m.mm[0], m.mm[1], m.mm[2]};
  const double n = norm(v);
  for (int i = 0; i < 3; ++i) u[i] = v[i] / n;
}

uint32_t events_of(const Move& m) {
  uint32_t e = 0;
  for (int32_t s : m.steps) e = std::max<uint32_t>(e, uint32_t(std::abs(s)));
  return e;
}

double length_of(const Move& m) {
  const double v[3] = {m.mm[0], m.mm[1], m.mm[2]};
  return norm(v);
}

// grbl's junction speed squared, in the textbook form.
double grbl_junction_sqr(const double (&u)[3], const double (&w)[3], double deviation,
                         const am::PathAxis (&axes)[3]) {
  const double cos_theta = -(u[0] * w[0] + u[1] * w[1] + u[2] * w[2]);
  if (cos_theta > 0.999999999999) return 0;  // a reversal
  double j[3] = {w[0] - u[0], w[1] - u[1], w[2] - u[2]};
  const double jn = norm(j);
  double a = 1e300;
  for (int i = 0; i < 3; ++i) {
    j[i] /= jn;
    if (j[i] != 0) a = std::min(a, axes[i].max_accel / axes[i].steps_per_mm / std::abs(j[i]));
  }
  const double h = std::sqrt(0.5 * (1 - cos_theta));
  return a * deviation * h / (1 - h);
}

// Path speed (mm/s) of an events/s value of the block of move m.
double path_speed(double events_per_s, const Move& m) { return events_per_s * length_of(m) / events_of(m); }

// Two orthonormal vectors: a plane of the sweep.
struct Plane {
  double e1[3], e2[3];
};

std::vector<Plane> planes() {
  std::vector<Plane> out = {{{1, 0, 0}, {0, 1, 0}}, {{0, 1, 0}, {0, 0, 1}}, {{0.6, 0.8, 0}, {0, 0, 1}}};
  std::mt19937 rng(5);
  std::normal_distribution<double> g;
  for (int k = 0; k < 4; ++k) {
    Plane p;
    double a[3] = {g(rng), g(rng), g(rng)}, b[3] = {g(rng), g(rng), g(rng)};
    const double na = norm(a);
    for (double& v : a) v /= na;
    const double dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    for (int i = 0; i < 3; ++i) b[i] -= dot * a[i];
    const double nb = norm(b);
    for (int i = 0; i < 3; ++i) {
      p.e1[i] = a[i];
      p.e2[i] = b[i] / nb;
    }
    out.push_back(p);
  }
  return out;
}

// Junction of two blocks: u along plane.e1, w turned away from it by the
// deflection (180 degrees - theta).
struct Pair {
  Move first, second;
  double expect_sqr;  // grbl, uncapped
};

Pair pair_at(const Plane& p, double theta_deg, double deviation, const am::PathAxis (&axes)[3]) {
  const double defl = (180 - theta_deg) * kPi / 180;
  double u[3], w[3];
  for (int i = 0; i < 3; ++i) {
    u[i] = p.e1[i];
    w[i] = std::cos(defl) * p.e1[i] + std::sin(defl) * p.e2[i];
  }
  // Long enough that neither block's ramp limits the junction: 2 a L >= 1.5 v^2.
  Pair out;
  double length = 1;
  for (int round = 0; round < 2; ++round) {
    out.first = move_along(u, length, axes);
    out.second = move_along(w, length, axes);
    if (theta_deg == 0) {  // exactly back
      for (int i = 0; i < 3; ++i) {
        out.second.mm[i] = -out.first.mm[i];
        out.second.steps[i] = -out.first.steps[i];
      }
    }
    double uf[3], wf[3];
    unit_of(out.first, uf);
    unit_of(out.second, wf);
    out.expect_sqr = grbl_junction_sqr(uf, wf, deviation, axes);
    // 100 mm/s^2: the slowest path acceleration; at most 5 km (steps fit).
    length = std::min(std::max(1.0, 1.5 * out.expect_sqr / (2 * 100.0)), 5e6);
  }
  return out;
}

TEST(PathJunction, MatchesGrblFormulaOver0To180Degrees) {
  std::vector<double> thetas = {0, 0.01, 0.05, 0.1, 0.25, 0.5};
  for (double t = 1; t < 180; t += 0.5) thetas.push_back(t);
  for (double t : {179.6, 179.7, 179.8, 179.9, 179.95}) thetas.push_back(t);
  double worst = 0, worst_theta = 0;
  int cases = 0;
  for (const Plane& plane : planes()) {
    for (double deviation : {0.002, 0.01, 0.05}) {
      for (double theta : thetas) {
        if (theta > 179.9 && deviation > 0.002) continue;  // blocks of more than 5 km
        const Pair pr = pair_at(plane, theta, deviation, kFast);
        Pair4 p(kFast, float(deviation), 2e9f);
        ASSERT_EQ(p.add(pr.first.steps, pr.first.mm, 0, true), Pair4::Status::queued);
        ASSERT_EQ(p.add(pr.second.steps, pr.second.mm, 0, true), Pair4::Status::queued);
        const am::PathBlock<3>* b = p.take();
        const double v = path_speed(b->exit, pr.first);
        if (theta == 0) {
          EXPECT_EQ(b->exit, 0.0f);
          continue;
        }
        const double err = std::abs(v * v / pr.expect_sqr - 1);
        ASSERT_LT(err, 5e-4) << "theta " << theta << " deviation " << deviation << " v^2 " << v * v
                             << " grbl " << pr.expect_sqr;
        if (err > worst) {
          worst = err;
          worst_theta = theta;
        }
        ++cases;
      }
    }
  }
  EXPECT_GT(cases, 7000);
  std::printf("junction: %d cases, worst |v^2 / grbl - 1| = %.2e at theta %.2f deg\n", cases, worst, worst_theta);
}

// With a feed, the junction is min(formula, both nominal speeds): straight on
// it is the nominal; two feeds meet at the slower one.
TEST(PathJunction, CappedByBothNominalSpeeds) {
  const Plane plane = planes()[4];
  for (double theta = 90; theta <= 180; theta += 0.25) {
    const Pair pr = pair_at(plane, theta, 0.02, kFast);
    for (float feed1 : {600.0f, 6000.0f, 60000.0f}) {
      for (float feed2 : {900.0f, 60000.0f}) {
        Pair4 p(kFast, 0.02f, 2e9f);
        ASSERT_EQ(p.add(pr.first.steps, pr.first.mm, feed1, false), Pair4::Status::queued);
        ASSERT_EQ(p.add(pr.second.steps, pr.second.mm, feed2, false), Pair4::Status::queued);
        const am::PathBlock<3>* b = p.take();
        const double v = path_speed(b->exit, pr.first), cap = std::min(feed1, feed2) / 60.0;
        const double expect = std::min(cap * cap, pr.expect_sqr);
        ASSERT_NEAR(v * v, expect, 5e-4 * expect) << theta << " " << feed1 << " " << feed2;
        if (theta == 180) {
          ASSERT_NEAR(v, cap, 1e-6 * cap);
        }
      }
    }
  }
}

// Feeds a polyline (cumulative positions, steps rounded from them) through a
// 16-block ring; records every taken block, and whether the ring was full
// when it was taken (15 blocks queued behind it): all but the first 16 and
// the last 15.
struct Taken {
  am::PathBlock<3> block;
  double length;  // path length, mm
  bool behind;    // taken from a full ring
};

std::vector<Taken> run(const std::vector<std::array<double, 3>>& points, float feed) {
  Ring16 p(kAxes, 0.01f, 40000);
  std::vector<Taken> out;
  std::vector<double> lengths;
  auto take_one = [&](bool behind) {
    const am::PathBlock<3>* b = p.take();
    EXPECT_NE(b, nullptr);
    const float ramp = 2.0f * b->accel * float(b->events);
    EXPECT_LE(b->entry * b->entry, b->exit * b->exit + ramp);
    EXPECT_LE(b->exit * b->exit, b->entry * b->entry + ramp);
    EXPECT_LE(std::max(b->entry, b->exit), b->cruise);
    out.push_back({*b, lengths[out.size()], behind});
    p.done();
  };
  int64_t at[3];
  for (int i = 0; i < 3; ++i) at[i] = std::llround(points[0][i] * kAxes[i].steps_per_mm);
  for (size_t k = 1; k < points.size(); ++k) {
    Move m{};
    double mm[3];
    for (int i = 0; i < 3; ++i) {
      const int64_t to = std::llround(points[k][i] * kAxes[i].steps_per_mm);
      m.steps[i] = int32_t(to - at[i]);
      at[i] = to;
      mm[i] = points[k][i] - points[k - 1][i];
      m.mm[i] = float(mm[i]);
    }
    if (p.full()) take_one(true);
    EXPECT_EQ(p.add(m.steps, m.mm, feed, false), Ring16::Status::queued);
    lengths.push_back(norm(mm));
  }
  while (!p.empty()) take_one(false);
  return out;
}

double path_speed(const Taken& t, double events_per_s) { return events_per_s * t.length / t.block.events; }

std::vector<std::array<double, 3>> circle(int segments, double chord) {
  const double r = chord / (2 * std::sin(kPi / segments));
  std::vector<std::array<double, 3>> pts;
  for (int k = 0; k <= segments; ++k) {
    const double a = 2 * kPi * k / segments;
    pts.push_back({r * std::cos(a), r * std::sin(a), 0});
  }
  return pts;
}

TEST(PathPolyline, CircleOfShortChordsRunsAtTheFeed) {
  // 30 mm/s; the junctions allow about 300, and the 1.5 mm queued behind a
  // taken block can stop from 38 (v^2 = 2 a L, a >= 500 mm/s^2). From rest
  // the feed is reached within 1 mm (10 blocks).
  const auto taken = run(circle(300, 0.1), 1800);
  ASSERT_EQ(taken.size(), 300u);
  int behind = 0;
  for (size_t k = 0; k < taken.size(); ++k) {
    const Taken& t = taken[k];
    if (!t.behind) continue;
    ++behind;
    ASSERT_GT(t.block.exit, 0.0f) << k;
    if (k < 20) continue;
    ASSERT_NEAR(path_speed(t, t.block.exit), 30.0, 30 * 1e-5) << k;
    ASSERT_NEAR(path_speed(t, t.block.entry), 30.0, 30 * 1e-5) << k;
  }
  EXPECT_EQ(behind, 300 - 16);
  EXPECT_EQ(taken.back().block.exit, 0.0f);
}

// Too fast for the queue: the 15 blocks (1.5 mm) behind each taken one must
// be able to stop, v^2 <= 2 a 1.5 mm with a >= 500 mm/s^2 (Y): no vertex is a
// stop, every one at least 38 mm/s.
TEST(PathPolyline, CircleAboveWhatTheQueueCanStopFromDoesNotStop) {
  const auto taken = run(circle(300, 0.1), 30000);
  double slowest = 1e9;
  for (size_t k = 20; k < taken.size(); ++k) {  // after the start from rest
    if (taken[k].behind) slowest = std::min(slowest, path_speed(taken[k], taken[k].block.exit));
  }
  EXPECT_GT(slowest, 38.0);
  EXPECT_LT(slowest, 60.0);  // and the queue does limit it: the feed is 500 mm/s
  EXPECT_EQ(taken.back().block.exit, 0.0f);
}

// 90 degree corners between 1 mm legs at +-45 degrees: every vertex runs at
// grbl's junction speed (the change of direction is along Y: a = 500 mm/s^2).
TEST(PathPolyline, ZigZagCornersAtTheJunctionSpeed) {
  std::vector<std::array<double, 3>> pts = {{0, 0, 0}};
  for (int k = 1; k <= 200; ++k) {
    const double s = 1 / std::sqrt(2.0);
    pts.push_back({pts.back()[0] + s, pts.back()[1] + (k % 2 ? s : -s), 0});
  }
  const double h = std::sin(kPi / 4), expect = 500 * 0.01 * h / (1 - h);
  const auto taken = run(pts, 3000);
  int checked = 0;
  for (const Taken& t : taken) {
    if (!t.behind) continue;
    const double v = path_speed(t, t.block.exit);
    ASSERT_NEAR(v * v, expect, 5e-4 * expect);
    ++checked;
  }
  EXPECT_EQ(checked, 200 - 16);
  EXPECT_EQ(taken.back().block.exit, 0.0f);
}

// Collinear segments of 0.5 .. 2 mm: straight on at the feed, never slower.
TEST(PathPolyline, CollinearSegmentsRunStraightThrough) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.5, 2);
  std::vector<std::array<double, 3>> pts = {{1, 2, 0.5}};
  for (int k = 0; k < 400; ++k) {
    const double l = u(rng);
    pts.push_back({pts.back()[0] + 0.48 * l, pts.back()[1] + 0.64 * l, pts.back()[2] + 0.6 * l});
  }
  const auto taken = run(pts, 600);  // 10 mm/s: Z (10 mm/s at most) runs at 6
  for (size_t k = 20; k < taken.size(); ++k) {  // from rest the feed is reached within 0.5 mm
    const Taken& t = taken[k];
    if (!t.behind) continue;
    ASSERT_NEAR(path_speed(t, t.block.exit), 10.0, 1e-5 * 10);
    ASSERT_NEAR(t.block.exit, t.block.cruise, 1e-5 * t.block.cruise);
  }
  EXPECT_EQ(taken.back().block.exit, 0.0f);
}

}  // namespace
