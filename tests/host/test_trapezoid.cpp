// TrapezoidRuns (core/motion/trapezoid.h) against an independent long double
// model of the ideal motion: every event of every case is placed at its
// actual tick and compared with the ideal position there. Also: how each
// planned run is split into parts, the runs per second at the Uno's fast
// axis, and the schedules the chip computes (bit for bit).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "core/motion/trapezoid.h"
#include "tools/golden/trapezoid_golden.h"

namespace am {
// Reads the generator's state between calls: which call plans a run (float
// work) and which only hands out a part of it.
struct TrapezoidProbe {
  template <class R>
  static bool pending(const BasicTrapezoidRuns<R>& r) {
    return r.left_[0] | r.left_[1];
  }
  template <class R>
  static bool cruise_next(const BasicTrapezoidRuns<R>& r) {
    return !pending(r) && r.done_ >= r.edge_[0] && r.n_ - r.done_ > r.edge_[1];
  }
  // The next call plans a ramp run or the event across a phase boundary.
  template <class R>
  static bool plans_next(const BasicTrapezoidRuns<R>& r) {
    return !pending(r) && r.done_ != r.n_ && !cruise_next(r);
  }
  template <class R>
  static bool accelerating_next(const BasicTrapezoidRuns<R>& r) {
    return r.done_ + 1 < r.edge_[0];
  }
  template <class R>
  static bool decelerating_next(const BasicTrapezoidRuns<R>& r) {
    return r.n_ - r.done_ < r.edge_[1];
  }
};
}  // namespace am

namespace {

using am::TrapezoidProbe;

using am::StepRun;
using am::TrapezoidBlock;

constexpr uint32_t kLongestInterval = 256u * 65536u;
const uint32_t kTickRates[] = {16000000, 8000000, 20000000};

// The ideal motion of a block, in long double and seconds, written from the
// contract: closed-form phase times, position as a function of time.
struct Ideal {
  enum Shape { cruise_only, trapezoid, triangle, all_decel, all_accel, kShapes };
  uint32_t c;  // ceil(tick_hz / cruise), exact
  long double n, a, v0, v1, vp, d_accel, t_accel, t_cruise, t_end;
  Shape shape;

  Ideal(const TrapezoidBlock& b, uint32_t tick_hz) : n(b.events), a(b.accel) {
    // A float significand times an integer below 2^33 is exact in long double.
    const long double f = tick_hz, cruise = b.cruise;
    c = uint32_t(ceill(f / cruise));
    while (c > 1 && (c - 1) * cruise >= f) --c;
    while (c * cruise < f) ++c;
    const long double top = f / c;
    v0 = std::min<long double>(b.entry, top);
    v1 = std::min<long double>(b.exit, top);
    shape = trapezoid;
    if (v1 * v1 > v0 * v0 + 2 * a * n) {
      v1 = sqrtl(v0 * v0 + 2 * a * n);
      shape = all_accel;
    } else if (v0 * v0 > v1 * v1 + 2 * a * n) {
      v1 = sqrtl(v0 * v0 - 2 * a * n);
      shape = all_decel;
    }
    const long double peak_sq = a * n + (v0 * v0 + v1 * v1) / 2;
    vp = peak_sq >= top * top ? top : sqrtl(peak_sq);
    if (shape == trapezoid && vp < top) shape = triangle;
    if (shape == trapezoid && v0 == top && v1 == top) shape = cruise_only;
    d_accel = (vp * vp - v0 * v0) / (2 * a);
    const long double d_decel = (vp * vp - v1 * v1) / (2 * a);
    t_accel = (vp - v0) / a;
    t_cruise = std::max<long double>(0, n - d_accel - d_decel) / vp;
    t_end = t_accel + t_cruise + (vp - v1) / a;
  }

  long double position(long double t) const {
    if (t <= t_accel) return v0 * t + a * t * t / 2;
    if (t <= t_accel + t_cruise) return d_accel + vp * (t - t_accel);
    if (t <= t_end) {
      const long double s = t_end - t;
      return n - v1 * s - a * s * s / 2;
    }
    return n + v1 * (t - t_end);  // the next block goes on at the exit speed
  }
};

const char* const kShapeNames[] = {"cruise only (entry = exit = cruise)", "trapezoid",
                                   "triangle", "pure deceleration (entry too high)",
                                   "pure acceleration (exit lowered)"};

struct Outcome {
  long double worst = 0;  // max |e - x(t_e)| over the block, events
  uint64_t end_ticks = 0;  // the last event's tick, from the block's start
  uint32_t runs = 0;
  std::string broken;  // the first rule broken, empty if none
};

// Runs one block through `runs` and checks every event. `offset` (s) is
// added to the block's clock for the reference: 0 compares with the block's
// own ideal motion.
template <class Runs>
Outcome run_block(Runs& runs, const TrapezoidBlock& b, uint32_t tick_hz, long double offset = 0) {
  Outcome out;
  const Ideal ideal(b, tick_hz);
  if (!runs.start(b, tick_hz)) {
    out.broken = "refused";
    return out;
  }
  const long double per_tick = 1.0L / tick_hz;
  uint64_t t = 0, e = 0;
  for (;;) {
    const StepRun r = runs.next_run();
    if (r.count == 0) {
      if (r.interval != 0) out.broken = "end marker not {0,0}";
      break;
    }
    ++out.runs;
    if (r.interval < ideal.c) out.broken = "interval below ceil(tick_hz / cruise)";
    if (r.interval > kLongestInterval) out.broken = "interval above 256 * 65536";
    if (e + r.count > b.events) {
      out.broken = "more than N events";
      return out;
    }
    for (uint32_t j = 0; j < r.count; ++j) {
      t += r.interval;
      ++e;
      const long double err = fabsl(e - ideal.position(t * per_tick + offset));
      if (!(err <= out.worst)) out.worst = err;  // NaN shows as NaN
    }
    if (!out.broken.empty()) return out;
  }
  if (e != b.events) out.broken = "fewer than N events";
  if (runs.events_done() != b.events) out.broken = "events_done() != N";
  if (runs.next_run().count != 0) out.broken = "runs after the end";
  out.end_ticks = t;
  return out;
}

std::string describe(const TrapezoidBlock& b, uint32_t tick_hz) {
  char s[160];
  snprintf(s, sizeof s, "N=%u entry=%g cruise=%g exit=%g accel=%g tick_hz=%u", b.events,
           double(b.entry), double(b.cruise), double(b.exit), double(b.accel), tick_hz);
  return s;
}

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

const float kCruises[] = {10, 77.7f, 1000, 12345.6f, 99999, 250000};
const float kAccels[] = {10, 517, 33333, 2e6f, 1.5e8f, 2147483648.0f};
struct SpeedPair {
  float entry, exit;  // fractions of the cruise speed
};
const SpeedPair kSpeedPairs[] = {{0, 0},     {1, 1},        {1, 0},      {0, 1},
                                 {0.37f, 0.81f}, {0.9f, 0.05f}, {1.5f, 2}, {0.999f, 0.6f}};
constexpr int kPairs = sizeof kSpeedPairs / sizeof kSpeedPairs[0];

TrapezoidBlock block(uint32_t n, float cruise, float accel, const SpeedPair& p) {
  return TrapezoidBlock{n, p.entry * cruise, cruise, p.exit * cruise, accel};
}

// Long blocks where float rounding matters most: long ramps (10^6 events of
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

// Each planned run is split into parts of q and q + 1 ticks that alternate,
// long ones first while accelerating and short ones first while
// decelerating, and whose partial sums stay within 3/16 of an interval (or
// one tick) of the run's straight line, on the side of the ideal motion:
// later while accelerating, earlier while decelerating. Two parts would not
// do: their bend would be up to k / 4 ticks off.
struct PartsTally {
  uint64_t runs = 0, parts = 0, multi = 0;
  double worst_two_part = 0;  // events: r (k - r) / k ticks at the bend of two parts, per mean interval
  int failures = 0;
};

void check_run(const std::vector<StepRun>& parts, bool accel, bool decel, const std::string& where,
               PartsTally& tally) {
  if (parts.empty()) return;
  int64_t k = 0, t = 0;
  for (const StepRun& p : parts) {
    k += p.count;
    t += int64_t(p.interval) * p.count;
  }
  const int64_t q = t / k, r = t - q * k, lim = std::max<int64_t>(t * 3 >> 4, k);
  ++tally.runs;
  tally.parts += parts.size();
  if (parts.size() > 2) ++tally.multi;
  tally.worst_two_part = std::max(tally.worst_two_part, double(r) * double(k - r) / double(t));
  std::string broken;
  if (r && parts[0].interval != (accel ? q + 1 : q)) broken = "first part of the wrong kind";
  int64_t j = 0, sum = 0;
  for (size_t i = 0; i < parts.size(); ++i) {
    if (parts[i].interval != q && parts[i].interval != q + 1) broken = "interval other than q, q + 1";
    if (i && parts[i].interval == parts[i - 1].interval) broken = "two parts of one kind in a row";
    j += parts[i].count;
    sum += int64_t(parts[i].interval) * parts[i].count;
    const int64_t lag = sum * k - j * t;  // k-scaled ticks behind the straight line
    if ((accel && (lag < 0 || lag > lim)) || (decel && (lag > 0 || lag < -lim)) || (!accel && !decel && k != 1))
      broken = "part off its side of the straight line";
  }
  if (!broken.empty() && ++tally.failures <= 10) ADD_FAILURE() << where << ": " << broken;
}

void check_parts(const TrapezoidBlock& b, uint32_t tick_hz, PartsTally& tally) {
  am::TrapezoidRuns runs;
  ASSERT_TRUE(runs.start(b, tick_hz)) << describe(b, tick_hz);
  std::vector<StepRun> parts;
  bool accel = false, decel = false;
  for (;;) {
    const bool plans = TrapezoidProbe::plans_next(runs), pending = TrapezoidProbe::pending(runs);
    if (plans || !pending) {
      check_run(parts, accel, decel, describe(b, tick_hz), tally);
      parts.clear();
      accel = TrapezoidProbe::accelerating_next(runs);
      decel = TrapezoidProbe::decelerating_next(runs);
    }
    const StepRun r = runs.next_run();
    if (!r.count) break;
    if (plans || pending) parts.push_back(r);
  }
}

TEST(TrapezoidParts, EachRunStaysOnTheIdealSideOfItsStraightLine) {
  PartsTally tally;
  check_parts({65000, 0, 160000, 0, 400000}, 16000000, tally);
  check_parts({2500, 0, 40000, 0, 800000}, 16000000, tally);
  check_parts({1000000, 0, 250000, 0, 10}, 16000000, tally);
  const float cruises[] = {1000, 12345.6f, 99999, 250000};
  const float accels[] = {517, 33333, 2e6f, 1.5e8f};
  const SpeedPair pairs[] = {{0, 0}, {0.37f, 0.81f}, {0.9f, 0.05f}, {1.5f, 2}};
  for (uint32_t tick_hz : kTickRates)
    for (float cruise : cruises)
      for (float accel : accels)
        for (const SpeedPair& p : pairs)
          for (uint32_t n : {4000u, 15000u}) check_parts(block(n, cruise, accel, p), tick_hz, tally);
  printf("TrapezoidParts: %llu runs planned, %.2f parts each, %.1f%% in more than two parts; "
         "two parts would bend up to %.2f event off the straight line\n",
         (unsigned long long)tally.runs, double(tally.parts) / double(tally.runs),
         100.0 * double(tally.multi) / double(tally.runs), tally.worst_two_part);
  EXPECT_EQ(tally.failures, 0);
  EXPECT_GT(tally.multi, 0u);
  EXPECT_GT(tally.worst_two_part, 0.5);  // why two parts are not enough
}

// Float work per second of motion: runs planned and StepRuns handed out per
// second of the ramps (0 to v and back, at 16 MHz), and near the top speed
// (the last tenth of the speed while accelerating).
struct Rates {
  double plans, step_runs, plans_top, step_runs_top;
};

Rates ramp_rates(float v, float accel) {
  const uint32_t f = 16000000;
  const double ramp_events = double(v) * v / (2.0 * accel);
  am::TrapezoidRuns runs;
  EXPECT_TRUE(runs.start({uint32_t(2 * ramp_events) + 1000, 0, v, 0, accel}, f));
  uint64_t ticks = 0, ticks_top = 0, plans = 0, step_runs = 0, plans_top = 0, step_runs_top = 0;
  for (;;) {
    const bool cruise = TrapezoidProbe::cruise_next(runs), plans_next = TrapezoidProbe::plans_next(runs);
    const double done = runs.events_done();
    const StepRun r = runs.next_run();
    if (!r.count) break;
    if (cruise) continue;
    const uint64_t run_ticks = uint64_t(r.interval) * r.count;
    ticks += run_ticks;
    plans += plans_next;
    ++step_runs;
    if (done > 0.81 * ramp_events && done < ramp_events) {  // speed 0.9 v .. v
      ticks_top += run_ticks;
      plans_top += plans_next;
      ++step_runs_top;
    }
  }
  const double s = double(ticks) / f, s_top = double(ticks_top) / f;
  return Rates{plans / s, step_runs / s, plans_top / s_top, step_runs_top / s_top};
}

TEST(TrapezoidSpeed, RunsPerSecondOfMotion) {
  const struct {
    float v, accel;
    double most_plans, most_step_runs;
  } cases[] = {{160000, 400000, 560, 1800}, {40000, 800000, 850, 1600}};
  for (const auto& c : cases) {
    const Rates r = ramp_rates(c.v, c.accel);
    printf("TrapezoidSpeed: %g events/s at %g events/s^2, 16 MHz: %.0f runs planned and %.0f StepRuns "
           "per second of ramp; near the top %.0f and %.0f\n",
           double(c.v), double(c.accel), r.plans, r.step_runs, r.plans_top, r.step_runs_top);
    EXPECT_LE(r.plans, c.most_plans);
    EXPECT_LE(r.step_runs, c.most_step_runs);
  }
}

// The slowest events, a block of one event from rest to rest at the lowest
// accel accepted (2 / sqrt(accel) s), are clamped to one segment; every
// block still hands out exactly N events.
TEST(TrapezoidLimits, SlowestEventsAreClampedToOneSegment) {
  for (uint32_t f : kTickRates) {
    const float lowest = float(2.0L * f / kLongestInterval * f / kLongestInterval) * 1.001f;
    for (float accel : {lowest, 2 * lowest, 5.0f})
      for (uint32_t n : {1u, 2u, 3u, 4u, 7u})
        for (float entry : {0.0f, 0.5f}) {
          am::TrapezoidRuns runs;
          const TrapezoidBlock b{n, entry, 20000, 0, accel};
          ASSERT_TRUE(runs.start(b, f)) << describe(b, f);
          uint32_t events = 0, calls = 0;
          for (StepRun r = runs.next_run(); r.count && calls < 100; r = runs.next_run(), ++calls) {
            EXPECT_LE(r.interval, kLongestInterval) << describe(b, f);
            events += r.count;
          }
          EXPECT_EQ(events, n) << describe(b, f);
        }
  }
}

// Blocks where float rounding puts a planned run's mean interval just below
// the cruise interval c (found by a search over 200000 random blocks): no
// interval may be shorter than c all the same.
TEST(TrapezoidLimits, NoIntervalShorterThanTheCruiseInterval) {
  const struct {
    TrapezoidBlock b;
    uint32_t tick_hz;
  } cases[] = {
      {{448, 5.98427105f, 52.2782555f, 51.6359863f, 853419776.0f}, 20000000},
      {{1980, 6.58104801f, 36.0293808f, 34.2663918f, 366508992.0f}, 16000000},
      {{10133, 1185.70459f, 1318.49121f, 1057.31372f, 23742.5762f}, 20000000},
      {{1775, 3870.59448f, 3870.93945f, 3870.93945f, 78.6495438f}, 20000000},
      {{4, 6.90764141f, 11.4957151f, 10.1510868f, 40655652.0f}, 20000000},
  };
  for (const auto& c : cases) {
    am::TrapezoidRuns runs;
    const Outcome o = run_block(runs, c.b, c.tick_hz);
    EXPECT_TRUE(o.broken.empty()) << describe(c.b, c.tick_hz) << ": " << o.broken;
    EXPECT_LE(o.worst, 0.3L) << describe(c.b, c.tick_hz);
  }
}

// The schedules the chip computes: tools/golden/trapezoid_golden.h holds the
// blocks and the hashes the chip gave, and how they were made.
TEST(TrapezoidBitIdentity, SameSchedulesAsTheChip) {
  for (const am::golden::Block& g : am::golden::kBlocks) {
    EXPECT_EQ(am::golden::hash_block(g.b, g.tick_hz), g.hash) << describe(g.b, g.tick_hz);
  }
  const am::golden::ChainHash c = am::golden::hash_chain();
  EXPECT_EQ(c.step_runs, am::golden::kChainStepRuns);
  EXPECT_EQ(c.hash, am::golden::kChainHash);
}

}  // namespace
