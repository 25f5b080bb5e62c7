// TrapezoidRuns (core/motion/trapezoid.h): how each planned run is split
// into parts (each on the ideal side of its straight line), the runs per
// second at the Uno's fast axis, the interval limits, and the schedules the
// chip computes (bit for bit). The ideal-motion sweeps: test_trapezoid.cpp;
// the model: trapezoid_model.h.
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
#include "trapezoid_model.h"

namespace {

using namespace trapezoidtest;
using am::TrapezoidProbe;

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
