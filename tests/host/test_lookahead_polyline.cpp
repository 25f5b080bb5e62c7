// Lookahead (core/motion/lookahead.h) on polylines of short segments, the case
// look-ahead exists for: a 10 mm circle in 300 segments (0.105 mm each)
// streams through a 16-block ring while a step generator takes the oldest
// block (begin, lock, finish). The vertices must not stop: the path speed at
// them settles at the slowest of the feed, the junction limit and what the
// look-ahead can stop from, computed here independently. Every profile the
// generator gets is exactly feasible in its own units (events), in integers:
// it can go from entry to exit at its acceleration over its events, cruise
// >= max(entry, exit), cruise <= nominal; and consecutive blocks meet at the
// same path speed (to the rounding of events/s).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/motion/lookahead.h"

namespace {

// X 80 steps/mm, Y 100 steps/mm, both 300 mm/s and 1000 mm/s^2; Z unused.
const am::LookaheadAxis kAxes[3] = {{80000, 24000, 80000}, {100000, 30000, 100000}, {400000, 4000, 40000}};
constexpr double kAccelMm = 1000;  // mm/s^2 along any XY direction's limiting axis

struct Segment {
  int32_t steps[3];
  int32_t len[3];
};

// A closed polygon around a circle of diameter `mm`, from absolute targets
// (steps rounded from the coordinates, as the interpreter does).
std::vector<Segment> circle(double mm, int n) {
  std::vector<Segment> out;
  int32_t prev_c[2] = {int32_t(std::lround(mm / 2 * 10000)), 0};
  int32_t prev_s[2];
  for (int i = 0; i < 2; ++i) prev_s[i] = int32_t(std::lround(prev_c[i] * double(kAxes[i].steps_per_m) / 1e7));
  for (int k = 1; k <= n; ++k) {
    const double t = 2 * M_PI * k / n;
    const int32_t c[2] = {int32_t(std::lround(mm / 2 * std::cos(t) * 10000)),
                          int32_t(std::lround(mm / 2 * std::sin(t) * 10000))};
    Segment s{{0, 0, 0}, {c[0] - prev_c[0], c[1] - prev_c[1], 0}};
    for (int i = 0; i < 2; ++i) {
      const int32_t st = int32_t(std::lround(c[i] * double(kAxes[i].steps_per_m) / 1e7));
      s.steps[i] = st - prev_s[i];
      prev_s[i] = st;
      prev_c[i] = c[i];
    }
    out.push_back(s);
  }
  return out;
}

struct Executed {
  am::LookaheadMove<3> move;  // as locked
  uint32_t length;            // lu
};

// A profile is exactly feasible in events, in integers (a profile generator
// may check that strictly): it can go from entry to exit at its
// acceleration over its events, max(entry, exit) <= cruise <= nominal, and
// the cruise is no faster than the triangle's peak.
void expect_feasible(const am::LookaheadMove<3>& m, uint32_t length, int index) {
  (void)length;
  const uint64_t e2 = uint64_t(m.entry) * m.entry, x2 = uint64_t(m.exit) * m.exit;
  const uint64_t room = 2 * uint64_t(m.accel) * m.events;
  EXPECT_LE(e2, x2 + room) << "block " << index << ": cannot slow from entry to exit";
  EXPECT_LE(x2, e2 + room) << "block " << index << ": cannot speed from entry to exit";
  EXPECT_GE(m.cruise, std::max(m.entry, m.exit)) << "block " << index;
  EXPECT_LE(m.cruise, m.nominal) << "block " << index;
  EXPECT_LE(uint64_t(m.cruise) * m.cruise, (e2 + x2 + room) / 2 + 1) << "block " << index << ": peak";
}

double path_speed(uint32_t events_per_s, const Executed& e) {  // mm/s
  return double(events_per_s) * e.length / e.move.events / 10000.0;
}

// Streams the segments through a Size-block ring; the generator takes a
// block whenever the ring is full (and drains it at the end). Checks every
// planned profile after every add, on the way.
template <uint8_t Size>
std::vector<Executed> run(const std::vector<Segment>& segs, int32_t feed, uint32_t deviation = 100) {
  am::Lookahead<3, Size> p(kAxes, deviation);
  std::vector<Executed> done;
  auto take = [&]() {
    Executed e;
    ASSERT_TRUE(p.begin(e.move));
    e.length = p.block(0).length;
    ASSERT_TRUE(p.lock(e.move));
    EXPECT_TRUE(e.move.final);
    ASSERT_TRUE(p.finish());
    done.push_back(e);
  };
  for (const Segment& s : segs) {
    if (p.full()) take();
    EXPECT_EQ(p.add(s.steps, s.len, feed, false), am::LookaheadStatus::queued);
    for (uint8_t i = 0; i < p.size(); ++i) {
      am::LookaheadMove<3> m;
      p.move(i, m);
      expect_feasible(m, p.block(i).length, int(done.size()) + i);
    }
    am::LookaheadMove<3> last;
    p.move(uint8_t(p.size() - 1), last);
    EXPECT_EQ(last.exit, 0u);  // the queue's end stops
  }
  while (!p.empty()) take();
  return done;
}

// Vertex speeds (mm/s, from the exit of each block) and checks that hold
// for any run: feasibility, continuity, start and end at rest.
std::vector<double> check_run(const std::vector<Executed>& done) {
  std::vector<double> vertex;
  EXPECT_EQ(done.front().move.entry, 0u);
  EXPECT_EQ(done.back().move.exit, 0u);
  for (size_t k = 0; k < done.size(); ++k) {
    expect_feasible(done[k].move, done[k].length, int(k));
    if (k + 1 < done.size()) {
      // One path speed at the junction: each side rounded down by an event/s.
      const double out = path_speed(done[k].move.exit, done[k]), in = path_speed(done[k + 1].move.entry, done[k + 1]);
      const double slack = (double(done[k].length) / done[k].move.events +
                            double(done[k + 1].length) / done[k + 1].move.events) / 10000.0 + out * 1e-4;
      EXPECT_NEAR(out, in, slack) << "junction " << k;
      vertex.push_back(out);
    }
  }
  return vertex;
}

// The junction deviation limit (mm/s) of a regular polygon's vertex, here
// where both axes allow the same 1000 mm/s^2 (so the junction acceleration
// is min over X, Y of 1000 / |j_i|, j the unit turn vector).
double polygon_junction(int n, double direction) {
  const double turn = 2 * M_PI / n;
  const double h = std::cos(turn / 2);  // sin of half the interior angle
  const double jx = std::fabs(std::sin(direction)), jy = std::fabs(std::cos(direction));
  const double a = kAccelMm / std::max(jx, jy);
  return std::sqrt(a * 0.01 * h / (1 - h));
}

}  // namespace

TEST(LookaheadPolyline, ACircleOfShortSegmentsRunsAtItsFeedThroughEveryVertex) {
  // 3000 mm/min = 50 mm/s. Each 1.2 degree vertex allows several hundred
  // mm/s, and 15 queued blocks (1.57 mm) are enough to stop from 56 mm/s,
  // so every vertex runs at the feed.
  const std::vector<Segment> segs = circle(10.0, 300);
  const std::vector<Executed> done = run<16>(segs, 30000000);
  ASSERT_EQ(done.size(), segs.size());
  const std::vector<double> v = check_run(done);
  ASSERT_GT(polygon_junction(300, 0.0), 300.0);
  for (size_t k = 20; k + 20 < v.size(); ++k) EXPECT_NEAR(v[k], 50.0, 0.5) << "vertex " << k;
}

TEST(LookaheadPolyline, FasterThanTheRingCanStopFromItSettlesAtTheLookAheadSpeed) {
  // 12000 mm/min = 200 mm/s: the queue, not the feed or the vertices,
  // limits the speed. The generator takes the oldest block when 16 are
  // queued, so at the vertex after it 15 blocks remain before the queue's
  // end, and the speed there is what stops in them: v^2 = sum of 2 a L over
  // those 15, each segment's path acceleration that of its limiting axis,
  // min_i max_accel_i L / |steps_i| (about 1000 mm/s^2 along an axis, 1414
  // diagonally, and off by the rounding of a few steps per segment).
  const std::vector<Segment> segs = circle(10.0, 300);
  const std::vector<Executed> done = run<16>(segs, 120000000);
  const std::vector<double> v = check_run(done);
  double lo = 1e9, hi = 0;
  for (size_t k = 30; k + 30 < v.size(); ++k) {
    double room = 0;
    for (size_t j = k + 1; j <= k + 15; ++j) {
      const double l = std::hypot(double(segs[j].len[0]), double(segs[j].len[1]));  // lu
      double a = 1e300;                                                            // lu/s^2
      for (int i = 0; i < 2; ++i)
        if (segs[j].steps[i]) a = std::min(a, double(kAxes[i].max_accel) * l / std::abs(segs[j].steps[i]));
      room += 2 * a * l / 1e8;  // mm^2/s^2
    }
    const double want = std::sqrt(room);
    // Within 0.2 %: each 0.1 mm length is rounded down to 0.1 um (0.1 %, and
    // 2 a L goes with L^2), speeds to the event/s.
    EXPECT_NEAR(v[k], want, 0.002 * want) << "vertex " << k;
    lo = std::min(lo, v[k]);
    hi = std::max(hi, v[k]);
  }
  EXPECT_GT(lo, 55.0);
  EXPECT_LT(hi, 67.0);
}

TEST(LookaheadPolyline, ACoarsePolygonRunsAtItsJunctionSpeed) {
  // 30 segments (1.05 mm, 12 degree vertices) at 6000 mm/min: the vertices
  // limit, at the junction deviation speed of each (it depends on the
  // direction of the turn through the limiting axis). Each block can reach
  // the next vertex's speed, so every vertex runs at its own limit.
  const int n = 30;
  const std::vector<Segment> segs = circle(10.0, n);
  const std::vector<Executed> done = run<16>(segs, 60000000);
  const std::vector<double> v = check_run(done);
  for (size_t k = 3; k + 3 < v.size(); ++k) {
    // Vertex k joins segment k (direction 2 pi (k + 0.5) / n + pi / 2) and
    // k + 1; the turn vector points at the centre, along -(cos, sin) of
    // the vertex angle 2 pi (k + 1) / n.
    const double vertex_angle = 2 * M_PI * (k + 1) / n;
    const double want = polygon_junction(n, vertex_angle + M_PI / 2);
    EXPECT_NEAR(v[k], want, 0.002 * want + 0.02) << "vertex " << k;
    EXPECT_GT(v[k], 20.0);
  }
}

TEST(LookaheadPolyline, AllAtOnceInALargeRingTheCircleCruisesAtTheFeed) {
  // 60 segments in a 64-block ring, planned without anything taken: the
  // inner vertices are at the feed, the ends ramp from and to rest.
  const std::vector<Segment> segs = circle(10.0, 300);
  am::Lookahead<3, 64> p(kAxes);
  for (int k = 0; k < 60; ++k) ASSERT_EQ(p.add(segs[k].steps, segs[k].len, 30000000, false), am::LookaheadStatus::queued);
  for (uint8_t i = 15; i < 45; ++i) {
    am::LookaheadMove<3> m;
    p.move(i, m);
    const double mm_s = double(m.entry) * p.block(i).length / m.events / 10000.0;
    EXPECT_NEAR(mm_s, 50.0, 0.5) << int(i);
    EXPECT_TRUE(m.final) << int(i);  // at the feed: nothing can raise it
  }
  am::LookaheadMove<3> last;
  p.move(59, last);
  EXPECT_EQ(last.exit, 0u);
  EXPECT_FALSE(last.final);
}
