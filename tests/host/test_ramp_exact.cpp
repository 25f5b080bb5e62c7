// ExactRamp against closed-form constant-acceleration kinematics, and a
// measurement of how far the seed method (SpeedRamp) runs ahead of them.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/motion/speed_ramp.h"
#include "core/motion/speed_ramp_exact.h"

namespace {

// Ideal position (steps) at time t (s) of an N-step move from rest to rest:
// accelerate at a, cruise at v (or peak lower for a triangle), stop at d.
struct Kinematics {
  long double n, a, d, peak, t_accel, t_cruise, t_end;
  Kinematics(uint32_t steps, uint32_t rate, uint32_t accel, uint32_t decel)
      : n(steps), a(accel), d(decel) {
    const long double v = rate;
    peak = v * v / (2 * a) + v * v / (2 * d) <= n ? v : sqrtl(2 * n * a * d / (a + d));
    t_accel = peak / a;
    t_cruise = (n - peak * peak / (2 * a) - peak * peak / (2 * d)) / peak;
    t_end = t_accel + t_cruise + peak / d;
  }
  long double position(long double t) const {
    if (t <= t_accel) return a * t * t / 2;
    if (t <= t_accel + t_cruise) return peak * peak / (2 * a) + peak * (t - t_accel);
    if (t <= t_end) return n - d * (t_end - t) * (t_end - t) / 2;
    return n;
  }
};

struct Measured {
  long double max_deviation = 0;  // steps
  uint64_t total_ticks = 0;
  uint32_t steps = 0;
};

Measured measure_exact(uint32_t steps, const am::RampConfig& cfg) {
  am::ExactRamp ramp;
  EXPECT_EQ(ramp.plan(steps, cfg), am::RampError::none);
  const Kinematics ideal(steps, cfg.max_rate, cfg.accel, cfg.decel);
  Measured m;
  while (!ramp.finished()) {
    const uint32_t interval = ramp.next();
    EXPECT_GE(interval, 1u);
    m.total_ticks += interval;
    ++m.steps;
    const long double t = (long double)m.total_ticks / cfg.tick_hz;
    const long double dev = fabsl(ideal.position(t) - m.steps);
    if (dev > m.max_deviation) m.max_deviation = dev;
  }
  EXPECT_EQ(m.steps, steps);
  EXPECT_NEAR((long double)m.total_ticks, ideal.t_end * cfg.tick_hz, 1.0L);
  return m;
}

TEST(RampExact, EveryStepWithinHalfAStepOfIdealKinematics) {
  const uint32_t ticks[] = {1000000, 2000000, 16000000};
  const uint32_t rates[] = {1, 50, 670, 1000, 5000, 20000};
  const uint32_t accels[] = {3, 100, 3185, 10000, 200000};
  const uint32_t steps[] = {1, 2, 3, 10, 70, 400, 1001, 20000};
  long double worst = 0;
  int cases = 0, triangles = 0;
  for (uint32_t f : ticks)
    for (uint32_t v : rates)
      for (uint32_t a : accels)
        for (uint32_t d : {a, 2 * a, a / 3 + 1})
          for (uint32_t n : steps) {
            const am::RampConfig cfg{f, v, a, d};
            if (am::ExactRamp::check(cfg) != am::RampError::none) continue;
            const Measured m = measure_exact(n, cfg);
            EXPECT_LE(m.max_deviation, 0.5L) << f << " " << v << " " << a << " " << d << " " << n;
            if (m.max_deviation > worst) worst = m.max_deviation;
            ++cases;
            if (Kinematics(n, v, a, d).peak < v) ++triangles;
          }
  EXPECT_GE(cases, 1000);
  EXPECT_GE(triangles, 300);
  // Measured: one tick of rounding is the only error; docs/ramps.md quotes
  // the worst case over this grid: 0.0147 step, 1.5 ticks at 20000 steps/s on
  // a 1 MHz timer.
  EXPECT_LT(worst, 0.015L);
  RecordProperty("cases", cases);
  RecordProperty("triangles", triangles);
}

TEST(RampExact, AppendixMoveInSteps) {
  // seed-000's move in step units: 400 steps, 670 steps/s, 100 rad/s^2 at
  // 0.0314 rad/step = 3185 steps/s^2, 1 MHz.
  const am::RampConfig cfg{1000000, 670, 3185, 3185};
  am::ExactRamp ramp;
  ASSERT_EQ(ramp.plan(400, cfg), am::RampError::none);
  // First interval: f sqrt(2 / a) = 25059.2 us (the seed's 0.676 c0 is 16941).
  EXPECT_EQ(ramp.next(), 25059u);
  // Second: f (sqrt(4/a) - sqrt(2/a)) = 10379.7; the rounded absolute times
  // 35438.5 -> 35438 and 25059 give 10379.
  EXPECT_EQ(ramp.next(), 10379u);
  const Measured m = measure_exact(400, cfg);
  EXPECT_EQ(m.total_ticks, 807376u);  // 2 * 670/6370 + 400/670 s
}

TEST(RampExact, SeparateDecelAndCruiseLengths) {
  // 1000 steps at 1000 steps/s, a = 2000, d = 500 (1 MHz): ramps of 250 and
  // 1000 steps would need 1250 > 1000, so it is a triangle with the peak at
  // N d / (a + d) = 200 steps: v_peak = sqrt(2 * 2000 * 200) = 894.4 steps/s.
  const am::RampConfig cfg{1000000, 1000, 2000, 500};
  am::ExactRamp ramp;
  ASSERT_EQ(ramp.plan(1000, cfg), am::RampError::none);
  std::vector<uint32_t> intervals;
  while (!ramp.finished()) intervals.push_back(ramp.next());
  uint32_t shortest = intervals[0];
  size_t at = 0;
  for (size_t i = 0; i < intervals.size(); ++i)
    if (intervals[i] < shortest) shortest = intervals[i], at = i;
  EXPECT_NEAR(at + 1, 200u, 1u);
  EXPECT_NEAR(1e6 / shortest, 894.4, 2.0);
  // Decelerating 4x slower than it accelerated: the last interval is twice the
  // first (sqrt(2/d) vs sqrt(2/a)).
  EXPECT_NEAR(double(intervals.back()) / intervals.front(), 2.0, 0.001);
}

TEST(RampExact, RunsMatchSingleSteps) {
  const am::RampConfig cfg{16000000, 4000, 8000, 3000};
  am::ExactRamp single, grouped;
  ASSERT_EQ(single.plan(50000, cfg), am::RampError::none);
  ASSERT_EQ(grouped.plan(50000, cfg), am::RampError::none);
  uint64_t runs = 0;
  while (!grouped.finished()) {
    const am::StepRun run = grouped.next_run();
    ASSERT_GE(run.count, 1u);
    for (uint16_t i = 0; i < run.count; ++i) ASSERT_EQ(single.next(), run.interval);
    ++runs;
  }
  EXPECT_TRUE(single.finished());
  EXPECT_EQ(single.next(), 0u);
  EXPECT_EQ(grouped.next_run().count, 0u);
  // 16e6 / 4000 = 4000 exactly: the cruise is long runs, not one per step.
  EXPECT_LT(runs, 4000u);
}

TEST(RampExact, RejectsWhatItCannotTime) {
  am::ExactRamp ramp;
  EXPECT_EQ(ramp.plan(10, {1000000, 0, 100, 100}), am::RampError::zero_speed);
  EXPECT_EQ(ramp.plan(10, {1000000, 100, 0, 100}), am::RampError::zero_accel);
  EXPECT_EQ(ramp.plan(10, {1000000, 100, 100, 0}), am::RampError::zero_accel);
  EXPECT_EQ(ramp.plan(10, {1000000, 2000000, 100, 100}), am::RampError::rate_above_tick);
  EXPECT_EQ(ramp.plan(10, {1000000, 600000, 100000, 100000}), am::RampError::out_of_range);
  // A 16 MHz ramp to 10000 steps/s at 1 step/s^2 would last 10000 s.
  EXPECT_EQ(ramp.plan(10, {16000000, 10000, 1, 1}), am::RampError::out_of_range);
  EXPECT_EQ(ramp.plan(0, {1000000, 100, 100, 100}), am::RampError::none);
  EXPECT_TRUE(ramp.finished());
  EXPECT_EQ(ramp.next(), 0u);
}

// The seed method's c0 = 0.676 f sqrt(2/a) starts the ramp early, and every
// later step inherits that lead. Measured on Appendix 1's ramp in step units
// (1 MHz, 3185 steps/s^2, 670 steps/s): how much earlier step k comes than the
// ideal time sqrt(2k/a), and how many steps the motor is then ahead of the
// ideal position, both as a percentage. Figures quoted in docs/ramps.md.
TEST(RampExact, SeedMethodRunAheadMeasured) {
  const am::RampConfig cfg{1000000, 670, 3185, 3185};
  am::SpeedRamp seed;
  ASSERT_EQ(seed.plan(400, cfg), am::RampError::none);
  struct Row { int k; double time_lead_pct, position_ahead_pct; };
  const Row rows[] = {{1, 32.4, 54.3}, {2, 23.5, 41.5}, {5, 15.1, 27.8}, {10, 10.7, 20.2},
                      {20, 7.55, 14.5}, {50, 4.77, 9.32}, {70, 4.04, 7.91}};
  const long double a = cfg.accel;
  long double t = 0;
  int k = 0;
  for (const Row& row : rows) {
    while (k < row.k) t += seed.next() / 1e6L, ++k;
    const long double ideal_t = sqrtl(2.0L * k / a);
    const long double ideal_x = a * t * t / 2;
    EXPECT_NEAR(double((ideal_t - t) / ideal_t * 100), row.time_lead_pct, 0.06) << k;
    EXPECT_NEAR(double((k - ideal_x) / k * 100), row.position_ahead_pct, 0.06) << k;
    // "Several percent" early in the ramp, still above 4 % at its end.
    EXPECT_GT(double((ideal_t - t) / ideal_t), 0.04) << k;
  }
}

}  // namespace
