// FeedHold (core/motion/feed_hold.h) on the exact trapezoid: a block held at
// every run boundary of a sweep of blocks loses and adds no event, its stop
// never runs faster than the run before it and reaches rest in the distance
// and time constant deceleration gives, and its resume from rest ends at the
// planned exit or at the factor it reports.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/motion/feed_hold.h"

namespace {

using am::StepRun;
using am::TrapezoidBlock;

struct Held {
  uint32_t before = 0, stop = 0, held = 0, after = 0;  // events of each part
  bool broken = false;
};

// Runs `b`, holds after `boundary` runs, resumes once at rest.
Held hold_at(const TrapezoidBlock& b, uint32_t tick_hz, uint32_t boundary) {
  Held h;
  am::TrapezoidRuns runs;
  am::FeedHold hold;
  EXPECT_TRUE(runs.start(b, tick_hz));
  hold.begin(b);
  uint32_t last = 0;
  StepRun r{};
  for (uint32_t k = 0; k < boundary; ++k) {
    r = runs.next_run();
    if (!r.count) return h;  // the block ended first
    h.before += r.count;
    last = r.interval;
  }
  while (!runs.between_runs()) {
    r = runs.next_run();
    h.before += r.count;
    last = r.interval;
  }
  const double a = b.accel, f = tick_hz;
  const double v = h.before ? f / last : std::min<double>(b.entry, f / std::ceil(f / b.cruise));
  const uint32_t left = b.events - h.before;
  if (hold.stop(runs, last, tick_hz)) {
    double t = 0;
    for (r = runs.next_run(); r.count; r = runs.next_run()) {
      // Never faster than the speed the hold began at (a tick of rounding).
      if (last && r.interval + 1 < last) h.broken = true;
      h.stop += r.count;
      t += double(r.interval) * r.count / f;
    }
    const double need = v * v / (2 * a);
    if (need < left) {
      // To rest: ceil(v^2 / 2a) events, in about v / a (plus the half event
      // from rest and the tick rounding).
      EXPECT_EQ(h.stop, uint32_t(need) + 1);
      EXPECT_NEAR(t, v / a, 0.02 * v / a + 2.0 / v + std::sqrt(2 / a)) << v << " " << a;
      EXPECT_EQ(hold.carried(runs), 0.0f);
    } else {
      EXPECT_EQ(h.stop, left);
      if (b.exit > 0) {
        EXPECT_LE(hold.carried(runs), 1.0f + 1e-6f);
      }
    }
  }
  h.held = hold.held();
  const float slower = hold.resume(runs, tick_hz);
  EXPECT_LE(slower, 1.0f);
  for (r = runs.next_run(); r.count; r = runs.next_run()) h.after += r.count;
  if (h.held && b.exit > 0) {
    EXPECT_NEAR(runs.exit_speed(), b.exit * slower, b.exit * 1e-5f);
  }
  return h;
}

TEST(FeedHold, EveryBoundaryKeepsEveryEvent) {
  const TrapezoidBlock blocks[] = {
      {20000, 0, 20000, 0, 40000},  {5000, 3000, 20000, 3000, 100000}, {300, 0, 5000, 0, 1000},
      {100000, 0, 60000, 0, 500000}, {2000, 8000, 8000, 8000, 20000},  {1, 0, 100, 0, 1000},
      {7, 500, 600, 0, 10000},       {65000, 0, 160000, 0, 400000},
  };
  uint32_t holds = 0;
  for (const TrapezoidBlock& b : blocks) {
    for (uint32_t boundary = 0;; ++boundary) {
      const Held h = hold_at(b, 16000000, boundary);
      if (h.before == b.events || (boundary && !h.before && !h.stop)) break;  // past the end
      EXPECT_FALSE(h.broken) << b.events << " at run " << boundary;
      EXPECT_EQ(h.before + h.stop + h.held, b.events) << b.events << " at run " << boundary;
      EXPECT_EQ(h.after, h.held) << b.events << " at run " << boundary;
      ++holds;
    }
  }
  EXPECT_GT(holds, 1000u);
  printf("FeedHold: %u holds, every event kept\n", holds);
}

// From rest with nothing handed out: nothing runs, every event is held.
TEST(FeedHold, FromRestHoldsTheWholeBlock) {
  am::TrapezoidRuns runs;
  am::FeedHold hold;
  const TrapezoidBlock b{1000, 0, 5000, 0, 20000};
  ASSERT_TRUE(runs.start(b, 16000000));
  hold.begin(b);
  EXPECT_FALSE(hold.stop(runs, 0, 16000000));
  EXPECT_EQ(hold.held(), 1000u);
  EXPECT_EQ(hold.resume(runs, 16000000), 1.0f);
  uint32_t events = 0;
  for (StepRun r = runs.next_run(); r.count; r = runs.next_run()) events += r.count;
  EXPECT_EQ(events, 1000u);
}

}  // namespace
