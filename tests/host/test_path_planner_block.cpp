// PathPlanner (core/motion/path_planner.h), one block at a time: the path
// length (path axes, an extruder alone, from steps), the nominal speed and
// acceleration against each axis's limits for random directions (the limiting
// axis is at its limit, no axis above), the event-rate cap, the feed, the
// junctions around an extruder-only block, and the ring's bookkeeping (empty,
// full, bad feeds, take / done / clear, other sizes).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

#include "core/motion/path_planner.h"

namespace {

using Planner = am::PathPlanner<4, 8>;
using Block = am::PathBlock<4>;

// X, Y, Z and an extruder; unequal scales, rates and accelerations.
const am::PathAxis kAxes[4] = {{80, 16000, 80000, true},
                               {100, 20000, 50000, true},
                               {400, 4000, 40000, true},
                               {95, 9500, 95000, false}};
constexpr float kEventCap = 40000;

struct Move {
  int32_t steps[4];
  float mm[4];
};

// A move of mm[i] on each axis, steps rounded from it.
Move move_of(const double (&mm)[4]) {
  Move m{};
  for (int i = 0; i < 4; ++i) {
    m.mm[i] = float(mm[i]);
    m.steps[i] = int32_t(std::lround(mm[i] * kAxes[i].steps_per_mm));
  }
  return m;
}

uint32_t events_of(const Move& m) {
  uint32_t e = 0;
  for (int32_t s : m.steps) e = std::max<uint32_t>(e, uint32_t(std::abs(s)));
  return e;
}

// The path length the contract gives, in double.
double length_of(const Move& m) {
  double path = 0, other = 0;
  bool given = false;
  for (float v : m.mm) given |= v != 0;
  for (int i = 0; i < 4; ++i) {
    const double d = given ? double(m.mm[i]) : m.steps[i] / double(kAxes[i].steps_per_mm);
    (kAxes[i].in_path ? path : other) += d * d;
  }
  return std::sqrt(path > 0 ? path : other);
}

// Adds one move to an empty planner and takes it.
Block single(const Move& m, float feed, bool rapid, float cap = kEventCap) {
  Planner p(kAxes, 0.01f, cap);
  EXPECT_EQ(p.add(m.steps, m.mm, feed, rapid), Planner::Status::queued);
  const Block* b = p.take();
  EXPECT_NE(b, nullptr);
  return b ? *b : Block{};
}

TEST(PathBlock, StepsEventsAndRestAtBothEnds) {
  const Move m = move_of({3.0, -4.0, 0.25, 0.5});
  const Block b = single(m, 1200, false);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(b.steps[i], m.steps[i]);
  EXPECT_EQ(b.events, 400u);  // Y: 4 mm at 100 steps/mm
  EXPECT_EQ(b.entry, 0.0f);
  EXPECT_EQ(b.exit, 0.0f);
  // Path length from X, Y, Z only: sqrt(9 + 16 + 1/16); feed 20 mm/s.
  const double length = std::sqrt(25.0625);
  EXPECT_NEAR(b.cruise, 20.0 * 400 / length, 1e-6 * b.cruise);
}

TEST(PathBlock, DominantAxisIsTheFirstOfEquals) {
  const int32_t steps[4] = {-500, 500, 0, 500};
  const float mm[4] = {-6.25f, 5.0f, 0, 5.263f};
  Planner p(kAxes, 0.01f, kEventCap);
  ASSERT_EQ(p.add(steps, mm, 600, false), Planner::Status::queued);
  EXPECT_EQ(p.take()->events, 500u);
}

// Feed-limited moves in random directions: the nominal speed is the feed
// along the path, converted with events / L, and no axis exceeds its rate.
// Fast feeds and rapids: the limiting axis is exactly at its rate (or the
// dominant axis at the event cap), every other axis below.
TEST(PathBlock, RateAndAccelerationLimitsHonouredByTheLimitingAxis) {
  constexpr float kCap = 12000;  // below X's and Y's top rates
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  int feed_limited = 0, axis_limited = 0, cap_limited = 0;
  double worst = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    double mm[4];
    const double scale = std::exp(u(rng) * 4);  // 0.02 .. 55 mm
    for (int i = 0; i < 4; ++i) mm[i] = scale * u(rng) * (u(rng) < -0.6 ? 0 : 1);
    const Move m = move_of(mm);
    const uint32_t events = events_of(m);
    if (events == 0 || length_of(m) == 0) continue;
    const bool rapid = trial % 3 == 0;
    const float feed = float(std::exp(4 + 6 * (u(rng) + 1)));  // 55 .. 8.9e6 mm/min
    const Block b = single(m, feed, rapid, kCap);
    const double k = events / length_of(m);
    double rate_share = 0, accel_share = 0, expect = rapid ? 1e30 : feed / 60.0 * k;
    expect = std::min(expect, double(kCap));
    double expect_accel = 1e30;
    for (int i = 0; i < 4; ++i) {
      if (m.steps[i] == 0) continue;
      const double per_event = std::abs(m.steps[i]) / double(events);
      rate_share = std::max(rate_share, b.cruise * per_event / kAxes[i].max_rate);
      accel_share = std::max(accel_share, b.accel * per_event / kAxes[i].max_accel);
      expect = std::min(expect, kAxes[i].max_rate / per_event);
      expect_accel = std::min(expect_accel, kAxes[i].max_accel / per_event);
    }
    ASSERT_LE(rate_share, 1 + 1e-6) << trial;
    ASSERT_LE(b.cruise, kCap * (1 + 1e-6)) << trial;
    // The limiting axis runs at its acceleration, no axis above it.
    ASSERT_NEAR(accel_share, 1, 1e-6) << trial;
    ASSERT_NEAR(b.accel, expect_accel, 1e-6 * expect_accel) << trial;
    ASSERT_NEAR(b.cruise, expect, 1e-6 * expect) << trial;
    worst = std::max(worst, std::abs(b.cruise / expect - 1));
    if (std::abs(rate_share - 1) < 1e-6) {
      ++axis_limited;
    } else if (std::abs(b.cruise / kCap - 1) < 1e-6) {
      ++cap_limited;
    } else {
      ASSERT_FALSE(rapid) << trial;  // a rapid is always at an axis's rate or the cap
      ++feed_limited;
    }
  }
  EXPECT_GT(feed_limited, 500);
  EXPECT_GT(axis_limited, 500);
  EXPECT_GT(cap_limited, 10);
  EXPECT_LT(worst, 1e-6);
}

// The step generator's top rate caps the dominant axis, whatever the axes
// and the feed allow.
TEST(PathBlock, EventRateCap) {
  for (float cap : {500.0f, 3000.0f, 15999.0f}) {
    const Move m = move_of({100, 10, 0, 0});  // X dominant, 16000 steps/s allowed
    const Block rapid = single(m, 0, true, cap);
    EXPECT_FLOAT_EQ(rapid.cruise, cap);
    const Block fed = single(m, 1e6f, false, cap);
    EXPECT_FLOAT_EQ(fed.cruise, cap);
  }
  // Below the cap the axis rules.
  const Block b = single(move_of({100, 10, 0, 0}), 0, true, 1e6f);
  EXPECT_FLOAT_EQ(b.cruise, 16000);
}

// An extruder alone: its own distance is the path; the feed is along it.
TEST(PathBlock, ExtruderAloneIsItsOwnPath) {
  const Move m = move_of({0, 0, 0, -2.0});
  const Block b = single(m, 600, false);  // 10 mm/s of filament
  EXPECT_EQ(b.events, 190u);
  EXPECT_NEAR(b.cruise, 10.0 * 190 / 2.0, 1e-6 * b.cruise);
  EXPECT_NEAR(b.accel, 95000, 1e-6 * 95000);
}

// An extruder with XY: the path is XY; E only limits through its rate and
// acceleration.
TEST(PathBlock, ExtruderWithXyIsNotPartOfThePath) {
  const Move slow = move_of({3.0, 4.0, 0, 0.2});
  const Block b = single(slow, 1200, false);  // 20 mm/s along 5 mm of XY
  EXPECT_NEAR(b.cruise, 20.0 * 400 / 5.0, 1e-6 * b.cruise);
  // A large E share: E (9500 steps/s) limits, far below the feed.
  const Move fast = move_of({3.0, 4.0, 0, 40.0});
  const Block e = single(fast, 60000, false);
  ASSERT_EQ(e.events, 3800u);  // E dominates
  EXPECT_NEAR(e.cruise, 9500, 1e-6 * 9500);
  EXPECT_NEAR(e.accel, 95000, 1e-6 * 95000);
}

// A retract or prime (E alone) between two XY blocks in one line: it starts
// and ends at rest, so the XY blocks stop before it and start after it; with
// E along the path (extrusion) the line runs straight through.
TEST(PathBlock, ExtruderAloneStopsTheJunctionsAroundIt) {
  Planner p(kAxes, 0.01f, kEventCap);
  const Move xy = move_of({10, 0, 0, 0}), e = move_of({0, 0, 0, -1}), xye = move_of({10, 0, 0, 0.5});
  ASSERT_EQ(p.add(xy.steps, xy.mm, 3000, false), Planner::Status::queued);
  ASSERT_EQ(p.add(e.steps, e.mm, 1800, false), Planner::Status::queued);
  ASSERT_EQ(p.add(xy.steps, xy.mm, 3000, false), Planner::Status::queued);
  ASSERT_EQ(p.add(xye.steps, xye.mm, 3000, false), Planner::Status::queued);
  ASSERT_EQ(p.add(xy.steps, xy.mm, 3000, false), Planner::Status::queued);
  EXPECT_EQ(p.take()->exit, 0.0f);  // into the retract
  const Block* retract = p.take();
  EXPECT_EQ(retract->entry, 0.0f);
  EXPECT_EQ(retract->exit, 0.0f);
  EXPECT_EQ(p.take()->entry, 0.0f);  // out of it
  const Block* with_e = p.take();
  EXPECT_NEAR(with_e->entry, 50.0f * 80, 1e-3f);  // straight on at the feed, E or not
  EXPECT_NEAR(with_e->exit, 50.0f * 80, 1e-3f);
}

// No program distances at all: the length comes from steps / steps_per_mm.
TEST(PathBlock, LengthFromStepsWhenNoDistanceIsGiven) {
  const int32_t steps[4] = {240, -400, 0, 0};  // 3 mm X, -4 mm Y
  const float none[4] = {0, 0, 0, 0};
  Planner p(kAxes, 0.01f, kEventCap);
  ASSERT_EQ(p.add(steps, none, 1200, false), Planner::Status::queued);
  const Block* b = p.take();
  EXPECT_NEAR(b->cruise, 20.0 * 400 / 5.0, 1e-6 * b->cruise);
  // E alone, from steps.
  const int32_t e_steps[4] = {0, 0, 0, 95};
  ASSERT_EQ(p.add(e_steps, none, 600, false), Planner::Status::queued);
  const Block* e = p.take();
  EXPECT_NEAR(e->cruise, 10.0 * 95, 1e-6 * e->cruise);
}

TEST(PathPlannerRing, EmptyMovesQueueNothing) {
  Planner p(kAxes, 0.01f, kEventCap);
  const int32_t none[4] = {0, 0, 0, 0};
  const float mm[4] = {0.001f, 0, 0, 0};  // a distance too small for a step
  EXPECT_EQ(p.add(none, mm, 100, false), Planner::Status::empty);
  EXPECT_EQ(p.add(none, mm, 0, true), Planner::Status::empty);
  EXPECT_TRUE(p.empty());
  EXPECT_EQ(p.count(), 0);
  EXPECT_EQ(p.take(), nullptr);
}

TEST(PathPlannerRing, BadFeedsAreRefused) {
  Planner p(kAxes, 0.01f, kEventCap);
  const Move m = move_of({1, 1, 0, 0});
  for (float feed : {0.0f, -0.0f, -5.0f, NAN, -NAN, INFINITY, -INFINITY}) {
    EXPECT_EQ(p.add(m.steps, m.mm, feed, false), Planner::Status::bad_feed) << feed;
  }
  EXPECT_TRUE(p.empty());
  // A rapid ignores the feed.
  EXPECT_EQ(p.add(m.steps, m.mm, NAN, true), Planner::Status::queued);
  EXPECT_EQ(p.add(m.steps, m.mm, 0, true), Planner::Status::queued);
  EXPECT_EQ(p.count(), 2);
}

TEST(PathPlannerRing, FullTakeDoneAndClear) {
  Planner p(kAxes, 0.01f, kEventCap);
  const Move m = move_of({1, 0.5, 0, 0});
  for (int i = 0; i < 8; ++i) {
    EXPECT_FALSE(p.full());
    ASSERT_EQ(p.add(m.steps, m.mm, 3000, false), Planner::Status::queued);
  }
  EXPECT_TRUE(p.full());
  EXPECT_EQ(p.add(m.steps, m.mm, 3000, false), Planner::Status::full);
  // A taken block still counts until done().
  const Block* first = p.take();
  ASSERT_NE(first, nullptr);
  EXPECT_EQ(p.count(), 8);
  EXPECT_EQ(p.add(m.steps, m.mm, 3000, false), Planner::Status::full);
  p.done();
  EXPECT_EQ(p.count(), 7);
  EXPECT_EQ(p.add(m.steps, m.mm, 3000, false), Planner::Status::queued);
  // done() without a taken block changes nothing.
  Planner q(kAxes, 0.01f, kEventCap);
  ASSERT_EQ(q.add(m.steps, m.mm, 3000, false), Planner::Status::queued);
  q.done();
  EXPECT_EQ(q.count(), 1);
  // clear() forgets everything; the next block starts from rest.
  p.clear();
  EXPECT_TRUE(p.empty());
  EXPECT_EQ(p.take(), nullptr);
  ASSERT_EQ(p.add(m.steps, m.mm, 3000, false), Planner::Status::queued);
  ASSERT_EQ(p.add(m.steps, m.mm, 3000, false), Planner::Status::queued);
  const Block* b = p.take();
  EXPECT_EQ(b->entry, 0.0f);
  EXPECT_GT(b->exit, 0.0f);
}

// Other sizes instantiate and plan: one axis, five axes, a ring of two.
TEST(PathPlannerRing, OneAxisFiveAxesRingOfTwo) {
  using One = am::PathPlanner<1, 2>;
  const am::PathAxis one[1] = {{100, 10000, 50000, true}};
  One a(one, 0.01f, 20000);
  const int32_t s1[1] = {10000};
  const float m1[1] = {100};
  ASSERT_EQ(a.add(s1, m1, 6000, false), One::Status::queued);
  ASSERT_EQ(a.add(s1, m1, 6000, false), One::Status::queued);
  EXPECT_EQ(a.add(s1, m1, 6000, false), One::Status::full);
  EXPECT_NEAR(a.take()->exit, 10000, 1e-3);  // straight on at the feed (100 mm/s)
  using Five = am::PathPlanner<5, 32>;
  const am::PathAxis five[5] = {{80, 16000, 80000, true},  {80, 16000, 80000, true}, {400, 4000, 40000, true},
                                {95, 9500, 95000, false}, {95, 9500, 95000, false}};
  Five f(five, 0.01f, 40000);
  const int32_t s5[5] = {80, 80, 0, 10, 5};
  const float m5[5] = {1, 1, 0, 0.105f, 0.05f};
  ASSERT_EQ(f.add(s5, m5, 3000, false), Five::Status::queued);
  EXPECT_NEAR(f.take()->cruise, 50.0 * 80 / std::sqrt(2.0), 1e-3);
}

}  // namespace
