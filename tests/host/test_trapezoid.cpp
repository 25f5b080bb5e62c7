// TrapezoidRuns (core/motion/trapezoid.h) against an independent long double
// model of the ideal motion: every event of every case is placed at its
// actual tick and compared with the ideal position there. Also: how each
// planned run is split into parts, the runs per second at the Uno's fast
// axis, and the schedules the chip computes (bit for bit).
// This file: the ideal-motion sweeps, refusals, infeasible blocks, the start
// and the cruise; the runs' parts, speed, limits and bit identity:
// test_trapezoid_parts.cpp; the model: trapezoid_model.h.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "core/motion/trapezoid.h"
#include "trapezoid_model.h"

namespace {

using namespace trapezoidtest;

const char* const kShapeNames[] = {"cruise only (entry = exit = cruise)", "trapezoid",
                                   "triangle", "pure deceleration (entry too high)",
                                   "pure acceleration (exit lowered)"};

// Worst error per shape, printed at the end of a sweep.
struct Tally {
  struct Row {
    uint32_t cases = 0;
    uint64_t events = 0;
    long double worst = 0;
    std::string where;
  } rows[Ideal::kShapes];
  long double worst = 0;
  uint32_t failures = 0;

  template <class Runs>
  void add(Runs& runs, const TrapezoidBlock& b, uint32_t tick_hz) {
    const Outcome o = run_block(runs, b, tick_hz);
    if (!o.broken.empty() || !(o.worst <= 0.5L)) {
      if (++failures <= 10)
        ADD_FAILURE() << describe(b, tick_hz) << ": "
                      << (o.broken.empty() ? "error " + std::to_string(double(o.worst)) : o.broken);
      return;
    }
    Row& row = rows[Ideal(b, tick_hz).shape];
    ++row.cases;
    row.events += b.events;
    if (o.worst > row.worst) {
      row.worst = o.worst;
      row.where = describe(b, tick_hz);
    }
    if (o.worst > worst) worst = o.worst;
  }
  void print(const char* title) const {
    printf("%s\n", title);
    for (int s = 0; s < Ideal::kShapes; ++s)
      printf("  %-38s %5u cases %9llu events  worst %.4f event  (%s)\n", kShapeNames[s],
             rows[s].cases, (unsigned long long)rows[s].events, double(rows[s].worst),
             rows[s].where.c_str());
  }
};

// acceleration), high speeds on long ramps, a long slow cruise.
const TrapezoidBlock kLongBlocks[] = {
    {1000000, 0, 250000, 0, 10},          {1000000, 0, 250000, 0, 10000},
    {1000000, 100, 100, 100, 10},         {1000000, 0, 100, 0, 10},
    {1000000, 250000, 250000, 0, 20000},  {1000000, 0, 250000, 250000, 30000},
    {1000000, 3000, 250000, 2000, 10},    {1000000, 240000, 250000, 0, 31000},
    {999999, 0, 12345.6f, 17.5f, 10.5f},  {1000000, 5, 250000, 77, 99.9f},
};

TEST(TrapezoidSweep, EveryEventWithinHalfAnEventOfTheIdealMotion) {
  Tally tally;
  am::TrapezoidRuns runs;
  const uint32_t kShortN[] = {1, 2, 3, 4, 7, 19, 60, 250, 1000, 4000};
  int combo = 0;
  for (uint32_t tick_hz : kTickRates)
    for (float cruise : kCruises)
      for (float accel : kAccels) {
        for (const SpeedPair& p : kSpeedPairs)
          for (uint32_t n : kShortN) tally.add(runs, block(n, cruise, accel, p), tick_hz);
        // Longer blocks, one speed pair each, rotating through them.
        tally.add(runs, block(15000, cruise, accel, kSpeedPairs[combo % kPairs]), tick_hz);
        if (combo % 3 == 0)
          tally.add(runs, block(120000, cruise, accel, kSpeedPairs[combo / 3 % kPairs]), tick_hz);
        if (combo % 9 == 0)
          tally.add(runs, block(1000000, cruise, accel, kSpeedPairs[combo / 9 % kPairs]), tick_hz);
        ++combo;
      }
  for (uint32_t tick_hz : kTickRates)
    for (const TrapezoidBlock& b : kLongBlocks) tally.add(runs, b, tick_hz);
  tally.print("TrapezoidSweep: worst |e - x(t_e)| per shape");
  EXPECT_EQ(tally.failures, 0u);
  EXPECT_LE(tally.worst, 0.3L);
  for (const Tally::Row& row : tally.rows) EXPECT_GT(row.cases, 0u);  // every shape swept
}

// The same long blocks with the generator in long double: what float
// rounding adds to the method's own error.
TEST(TrapezoidFloatPrecision, LongBlocksFloatAgainstLongDouble) {
  long double worst_float = 0, worst_long = 0;
  for (uint32_t tick_hz : kTickRates)
    for (const TrapezoidBlock& b : kLongBlocks) {
      am::TrapezoidRuns in_float;
      am::BasicTrapezoidRuns<long double> in_long;
      const Outcome f = run_block(in_float, b, tick_hz), l = run_block(in_long, b, tick_hz);
      EXPECT_TRUE(f.broken.empty() && l.broken.empty()) << describe(b, tick_hz);
      worst_float = std::max(worst_float, f.worst);
      worst_long = std::max(worst_long, l.worst);
    }
  printf("TrapezoidFloatPrecision: 10^6-event blocks, worst error float %.4f, long double %.4f\n",
         double(worst_float), double(worst_long));
  // The method's own bound: 3/16 for the chord and the parts' window, half a
  // tick at each end of a run, a few percent for the speed change over a run.
  EXPECT_LE(worst_long, 0.23L);
  EXPECT_LE(worst_float, 0.3L);
}

// Blocks chained as a planner hands them over: each entry is the previous
// block's exit_speed(), each block starts at the previous one's last event.
TEST(TrapezoidChain, ChainedBlocksStayWithinTheBound) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> unit(0, 1);
  const auto log_uniform = [&](double lo, double hi) { return lo * std::pow(hi / lo, unit(rng)); };
  long double worst_own = 0, worst_continuous = 0;
  for (uint32_t tick_hz : kTickRates) {
    am::TrapezoidRuns runs;
    float entry = 0;
    long double drift = 0;  // s: actual minus ideal time of the previous block's end
    for (int i = 0; i < 80; ++i) {
      const float cruise = float(log_uniform(10, 250000));
      const float accel = float(log_uniform(10, 2147483648.0));
      const uint32_t n = uint32_t(log_uniform(1, 30000));
      const float exit = i == 79 ? 0 : float(unit(rng) < 0.3 ? cruise : unit(rng) * cruise);
      const TrapezoidBlock b{n, entry, cruise, exit, accel};
      am::TrapezoidRuns replay = runs;  // the same generator, against the continuous reference
      const Outcome own = run_block(runs, b, tick_hz);
      const Outcome continuous = run_block(replay, b, tick_hz, drift);
      ASSERT_TRUE(own.broken.empty()) << describe(b, tick_hz) << ": " << own.broken;
      EXPECT_LE(own.worst, 0.5L) << describe(b, tick_hz);
      EXPECT_LE(continuous.worst, 0.5L) << describe(b, tick_hz);
      worst_own = std::max(worst_own, own.worst);
      worst_continuous = std::max(worst_continuous, continuous.worst);
      drift += (long double)own.end_ticks / tick_hz - Ideal(b, tick_hz).t_end;
      entry = runs.exit_speed();
    }
  }
  printf("TrapezoidChain: 240 blocks, worst error %.4f against each block's own start, "
         "%.4f against the unbroken chain\n",
         double(worst_own), double(worst_continuous));
}

TEST(TrapezoidRefusals, RefusesWhatItCannotRunAndChangesNothing) {
  const TrapezoidBlock good{5000, 0, 20000, 300, 40000};
  const uint32_t f = 16000000;
  const float nan = NAN, inf = INFINITY;
  const TrapezoidBlock bad[] = {
      {0, 0, 20000, 0, 40000},        {16777217, 0, 20000, 0, 40000},
      {5000, 0, 0, 0, 40000},         {5000, 0, -1, 0, 40000},
      {5000, 0, nan, 0, 40000},       {5000, 0, inf, 0, 40000},
      {5000, 0, 20000, 0, 0},         {5000, 0, 20000, 0, -5},
      {5000, 0, 20000, 0, nan},       {5000, 0, 20000, 0, inf},
      {5000, nan, 20000, 0, 40000},   {5000, inf, 20000, 0, 40000},
      {5000, -1, 20000, 0, 40000},    {5000, 0, 20000, nan, 40000},
      {5000, 0, 20000, inf, 40000},   {5000, 0, 20000, -0.5f, 40000},
      {5000, 0, 0.9f, 0, 40000},      // slower than one event per 2^24 ticks
      {5000, 0, 20000, 0, 1.8f},      // first event from rest: f sqrt(2/a) > 2^24 ticks
  };
  am::TrapezoidRuns runs, untouched;
  ASSERT_TRUE(runs.start(good, f));
  ASSERT_TRUE(untouched.start(good, f));
  for (int i = 0; i < 7; ++i) {
    runs.next_run();
    untouched.next_run();
  }
  for (const TrapezoidBlock& b : bad) EXPECT_FALSE(runs.start(b, f)) << describe(b, f);
  EXPECT_FALSE(runs.start(good, 0));
  EXPECT_EQ(runs.events_done(), untouched.events_done());
  EXPECT_EQ(runs.exit_speed(), untouched.exit_speed());
  for (;;) {  // the block goes on exactly as it would have
    const StepRun a = runs.next_run(), b = untouched.next_run();
    ASSERT_EQ(a.interval, b.interval);
    ASSERT_EQ(a.count, b.count);
    if (a.count == 0) break;
  }
  // The limits themselves are accepted, and -0 runs as 0.
  EXPECT_TRUE(runs.start({5000, -0.0f, 20000, -0.0f, 40000}, f));
  EXPECT_TRUE(run_block(runs, {5000, -0.0f, 20000, -0.0f, 40000}, f).broken.empty());
  EXPECT_TRUE(runs.start({16777216, 0, 20000, 0, 40000}, f));
  EXPECT_TRUE(runs.start({5000, 0, 0.96f, 0, 40000}, f));
  EXPECT_TRUE(runs.start({5000, 0, 20000, 0, 1.9f}, f));
}

TEST(TrapezoidInfeasible, EntryTooHighDeceleratesAllTheWay) {
  const uint32_t f = 16000000;
  const TrapezoidBlock b{100, 1000, 1000, 0, 1000};  // needs 500 events to stop
  am::TrapezoidRuns runs;
  const Outcome o = run_block(runs, b, f);
  EXPECT_TRUE(o.broken.empty()) << o.broken;
  EXPECT_LE(o.worst, 0.3L);
  EXPECT_NEAR(runs.exit_speed(), std::sqrt(1000.0 * 1000 - 2 * 1000 * 100), 1e-3);
  // The entry is never raised: the first event comes no earlier than at the
  // entry speed.
  ASSERT_TRUE(runs.start(b, f));
  EXPECT_GE(runs.next_run().interval, 16000u);
  EXPECT_EQ(Ideal(b, f).shape, Ideal::all_decel);
}

TEST(TrapezoidInfeasible, ExitTooHighIsLowered) {
  const uint32_t f = 20000000;
  const TrapezoidBlock b{100, 0, 5000, 5000, 1000};  // reaches only sqrt(2 a N)
  am::TrapezoidRuns runs;
  const Outcome o = run_block(runs, b, f);
  EXPECT_TRUE(o.broken.empty()) << o.broken;
  EXPECT_LE(o.worst, 0.3L);
  EXPECT_NEAR(runs.exit_speed(), std::sqrt(2.0 * 1000 * 100), 1e-3);
  EXPECT_EQ(Ideal(b, f).shape, Ideal::all_accel);
}

TEST(TrapezoidInfeasible, FeasibleExitIsKeptAndCappedAtTheCruise) {
  am::TrapezoidRuns runs;
  ASSERT_TRUE(runs.start({1000, 0, 3000, 1234.5f, 50000}, 16000000));
  EXPECT_EQ(runs.exit_speed(), 1234.5f);
  // 16 MHz / 7000 is not whole: c = 2286 ticks, the top speed 6999.1 events/s.
  ASSERT_TRUE(runs.start({1000, 7000, 7000, 9000, 50000}, 16000000));
  EXPECT_FLOAT_EQ(runs.exit_speed(), 16000000.0f / 2286);
}

TEST(TrapezoidStart, FromRestTheFirstEventComesAtSqrtTwoOverAccel) {
  for (uint32_t f : kTickRates)
    for (float accel : kAccels) {
      am::TrapezoidRuns runs;
      ASSERT_TRUE(runs.start({50, 0, 250000, 0, accel}, f));
      const StepRun first = runs.next_run();
      const long double ideal = f * sqrtl(2.0L / accel);
      EXPECT_EQ(first.count, 1u);
      EXPECT_LE(fabsl(first.interval - ideal), 0.5L + ideal * 1e-6L)
          << f << " " << accel;
    }
}

TEST(TrapezoidCruise, LongSlowCruiseIsExactWholeTicks) {
  // 10^6 events at 100 events/s on 16 MHz: 10^4 s, 1.6e11 ticks.
  am::TrapezoidRuns runs;
  ASSERT_TRUE(runs.start({1000000, 100, 100, 100, 10}, 16000000));
  uint32_t events = 0, count = 0;
  for (StepRun r = runs.next_run(); r.count; r = runs.next_run()) {
    EXPECT_EQ(r.interval, 160000u);
    events += r.count;
    ++count;
  }
  EXPECT_EQ(events, 1000000u);
  EXPECT_EQ(count, 1000000u);  // 160000 ticks >= 2^17: one event per cruise run
}

// Cruise runs last under 2^17 ticks (a feed hold waits for what is queued):
// 65535 >> floor(log2 c) events each, at every cruise interval c.
TEST(TrapezoidCruise, CruiseRunsStayUnderTwoToTheSeventeenTicks) {
  for (uint32_t c = 1; c <= (1u << 24); c = c * 3 / 2 + 1) {
    am::TrapezoidRuns runs;
    const float v = 16000000.0f / float(c);
    ASSERT_TRUE(runs.start({200000, v, v, v, 1000}, 16000000)) << c;
    uint32_t events = 0;
    // Entry, cruise and exit alike: every run is a cruise run, at the
    // generator's whole-tick interval (c or c + 1 after float rounding).
    for (StepRun r = runs.next_run(); r.count; r = runs.next_run()) {
      uint32_t bits = 0;
      while ((r.interval >> bits) > 1) ++bits;
      const uint32_t cap = (65535u >> bits) ? (65535u >> bits) : 1;
      EXPECT_LE(r.interval - c, 1u) << c;
      EXPECT_EQ(r.count, std::min<uint32_t>(cap, 200000 - events)) << c;
      EXPECT_TRUE(uint64_t(r.count) * r.interval < (1u << 17) || r.count == 1) << c;
      events += r.count;
    }
    EXPECT_EQ(events, 200000u) << c;
  }
}

TEST(TrapezoidCruise, ExactCeilingOfTheCruiseInterval) {
  // Cruise speeds whose tick count is within float rounding of a whole
  // number: a float division would get some of them wrong by one tick.
  uint32_t checked = 0;
  for (uint32_t f : kTickRates)
    for (uint32_t c = 1000000; c < 1000400; ++c) {
      const float cruise = float((long double)f / c);  // just above or below f / c
      am::TrapezoidRuns runs;
      ASSERT_TRUE(runs.start({3, cruise, cruise, cruise, 1000}, f));
      EXPECT_EQ(runs.next_run().interval, Ideal({3, cruise, cruise, cruise, 1000}, f).c)
          << f << " " << cruise;
      ++checked;
    }
  EXPECT_EQ(checked, 1200u);
}

}  // namespace
