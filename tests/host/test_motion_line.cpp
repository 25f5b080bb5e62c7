// LineDda (core/motion/line_dda.h) against references computed here from the
// definitions: seed-002 §3's pulse lists (its DDA: L = round(sqrt(A^2 + B^2))
// iterations, pulse on accumulator overflow = DdaPhase::late), and for
// Bresenham (nearest) phase the k-th step of each minor axis on event
// ceil((k N - floor(N/2)) / n), every axis within half a step of the ideal
// line e n / N at every event, exact end on target.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "core/motion/line_dda.h"

namespace {

// Events (1-based) at which each axis steps, over the whole block.
template <uint8_t Axes>
std::vector<std::vector<uint32_t>> pulse_events(am::LineDda<Axes>& dda) {
  std::vector<std::vector<uint32_t>> events(Axes);
  uint32_t e = 0;
  while (!dda.finished()) {
    const am::StepEvent ev = dda.next();
    ++e;
    for (uint8_t i = 0; i < Axes; ++i)
      if (ev.axes & (1u << i)) events[i].push_back(e);
  }
  return events;
}

uint32_t seed_iterations(int32_t a, int32_t b) {
  return uint32_t(std::lround(std::sqrt(double(a) * a + double(b) * b)));
}

std::vector<uint32_t> range(uint32_t first, uint32_t last) {
  std::vector<uint32_t> v;
  for (uint32_t e = first; e <= last; ++e) v.push_back(e);
  return v;
}

TEST(MotionLineSeedVectors, PulseListsOfTheSeedDda) {
  struct Vector {
    int32_t a, b;
    uint32_t iterations;
    std::vector<uint32_t> x, y;
  };
  const Vector vectors[] = {
      {3, 4, 5, {2, 4, 5}, {2, 3, 4, 5}},
      {5, 0, 5, range(1, 5), {}},
      {10, 3, 10, range(1, 10), {4, 7, 10}},
      {7, 7, 10, {2, 3, 5, 6, 8, 9, 10}, {2, 3, 5, 6, 8, 9, 10}},
  };
  for (const Vector& v : vectors) {
    ASSERT_EQ(seed_iterations(v.a, v.b), v.iterations) << v.a << "," << v.b;
    am::LineDda<2> dda;
    const int32_t delta[2] = {v.a, v.b};
    ASSERT_TRUE(dda.start(delta, v.iterations, am::DdaPhase::late));
    EXPECT_EQ(dda.events(), v.iterations);
    const auto events = pulse_events(dda);
    EXPECT_EQ(events[0], v.x) << v.a << "," << v.b;
    EXPECT_EQ(events[1], v.y) << v.a << "," << v.b;
  }
  // (1000, 1000): L = 1414 iterations, 1000 pulses on each axis.
  am::LineDda<2> dda;
  const int32_t delta[2] = {1000, 1000};
  ASSERT_EQ(seed_iterations(1000, 1000), 1414u);
  ASSERT_TRUE(dda.start(delta, 1414, am::DdaPhase::late));
  const auto events = pulse_events(dda);
  EXPECT_EQ(events[0].size(), 1000u);
  EXPECT_EQ(events[1].size(), 1000u);
  EXPECT_EQ(events[0].back(), 1414u);  // the last iteration completes both axes
}

TEST(MotionLineSeedVectors, DominantClockGivesOneEventPerDominantStep) {
  // The same moves on the dominant axis's clock: N = max |delta| events.
  am::LineDda<2> dda;
  const int32_t delta[2] = {3, 4};
  ASSERT_TRUE(dda.start(delta));
  EXPECT_EQ(dda.events(), 4u);
  EXPECT_EQ(dda.dominant(), 1);
  const auto events = pulse_events(dda);
  EXPECT_EQ(events[1], range(1, 4));
  // x at ceil((k 4 - 2) / 3): k = 1, 2, 3 -> events 1, 2, 4 (positions round(3e/4)).
  EXPECT_EQ(events[0], (std::vector<uint32_t>{1, 2, 4}));
}

// Independent reference: event of the k-th step of an axis of n steps over N
// events, Bresenham phase h = floor(N / 2): the least e with e n + h >= k N.
uint64_t nearest_event(uint64_t k, uint64_t n, uint64_t big_n) {
  const uint64_t h = big_n / 2;
  return (k * big_n - h + n - 1) / n;
}

// Runs a 4-axis block and checks every event against the definitions.
void check_block(const int32_t (&delta)[4], uint32_t events_in, am::DdaPhase phase) {
  am::LineDda<4> dda;
  ASSERT_TRUE(dda.start(delta, events_in, phase));
  uint64_t dominant = 0;
  for (int32_t d : delta) dominant = std::max<uint64_t>(dominant, uint64_t(std::llabs(d)));
  const uint64_t big_n = events_in ? events_in : dominant;
  ASSERT_EQ(dda.events(), big_n);
  int64_t pos[4] = {0, 0, 0, 0};
  uint64_t next_k[4] = {1, 1, 1, 1};
  for (uint64_t e = 1; e <= big_n; ++e) {
    ASSERT_FALSE(dda.finished());
    ASSERT_EQ(dda.remaining(), big_n - e + 1);
    const am::StepEvent ev = dda.next();
    for (int i = 0; i < 4; ++i) {
      const uint64_t n = uint64_t(std::llabs(delta[i]));
      const bool steps = ev.axes & (1u << i);
      if (steps) {
        ASSERT_NE(n, 0u);
        EXPECT_EQ(bool(ev.dirs & (1u << i)), delta[i] > 0);
        pos[i] += delta[i] > 0 ? 1 : -1;
      }
      // The k-th step exactly on its event.
      const uint64_t due = next_k[i] <= n ? (phase == am::DdaPhase::nearest
                                                 ? nearest_event(next_k[i], n, big_n)
                                                 : (next_k[i] * big_n + n - 1) / n)
                                          : 0;
      ASSERT_EQ(steps, due == e) << "axis " << i << " event " << e;
      if (steps) ++next_k[i];
      // Deviation from the ideal line: |p - e n / N| <= 1/2 (nearest), < 1 (late).
      const int64_t p = pos[i] < 0 ? -pos[i] : pos[i];
      const int64_t twice_dev = 2 * p * int64_t(big_n) - 2 * int64_t(e * n);
      if (phase == am::DdaPhase::nearest) {
        ASSERT_LE(std::llabs(twice_dev), int64_t(big_n)) << "axis " << i << " event " << e;
      } else {
        ASSERT_LE(twice_dev, 0);
        ASSERT_GT(twice_dev, -2 * int64_t(big_n));
      }
    }
  }
  EXPECT_TRUE(dda.finished());
  for (int i = 0; i < 4; ++i) EXPECT_EQ(pos[i], delta[i]) << "axis " << i;
  for (int i = 0; i < 4; ++i) EXPECT_EQ(dda.count(uint8_t(i)), uint32_t(std::llabs(delta[i])));
}

TEST(MotionLineBresenham, RandomBlocksEveryStepOnScheduleAndExactEnd) {
  std::mt19937 rng(20240801);
  for (int trial = 0; trial < 1500; ++trial) {
    int32_t d[4];
    const int shape = trial % 6;
    const int32_t span = 1 + int32_t(rng() % (trial < 1000 ? 300 : 5000));
    for (int i = 0; i < 4; ++i) d[i] = int32_t(rng() % (2 * span + 1)) - span;
    if (shape == 1) d[1] = d[3] = 0;                 // idle axes
    if (shape == 2) d[2] = d[0], d[3] = -d[0];       // equal magnitudes (two dominants)
    if (shape == 3) d[1] = d[2] = d[3] = 0;          // one axis
    if (shape == 4) d[0] = d[1] = d[2] = d[3] = 0;   // empty block
    check_block(d, 0, am::DdaPhase::nearest);
    if (::testing::Test::HasFatalFailure()) return;
  }
}

TEST(MotionLineBresenham, MinorsOfAnOutsideClock) {
  // Axes riding along another interpolator's events (N > every |delta|).
  std::mt19937 rng(7);
  for (int trial = 0; trial < 400; ++trial) {
    int32_t d[4];
    for (int i = 0; i < 4; ++i) d[i] = int32_t(rng() % 801) - 400;
    const uint32_t n = 400 + rng() % 3000;
    check_block(d, n, trial % 2 ? am::DdaPhase::late : am::DdaPhase::nearest);
    if (::testing::Test::HasFatalFailure()) return;
  }
}

TEST(MotionLineBresenham, EmptyBlockAndRejectedInputs) {
  am::LineDda<3> dda;
  const int32_t zero[3] = {0, 0, 0};
  EXPECT_TRUE(dda.start(zero));
  EXPECT_EQ(dda.events(), 0u);
  EXPECT_TRUE(dda.finished());
  const int32_t minimum[3] = {5, -2147483647 - 1, 0};
  EXPECT_FALSE(dda.start(minimum));
  EXPECT_TRUE(dda.finished());
  const int32_t some[3] = {5, -9, 2};
  EXPECT_FALSE(dda.start(some, 8, am::DdaPhase::nearest));  // fewer events than |delta|
  EXPECT_TRUE(dda.finished());
  EXPECT_FALSE(dda.start(some, 0x80000000u, am::DdaPhase::nearest));
  EXPECT_TRUE(dda.start(some, 9, am::DdaPhase::nearest));
  EXPECT_EQ(dda.dirs(), 0b101);
}

// Positions after event e, from the definition.
int64_t nearest_position(uint64_t e, uint64_t n, uint64_t big_n) { return int64_t((e * n + big_n / 2) / big_n); }

TEST(MotionLineBresenham, FullMagnitudeDominantWithSmallMinors) {
  // N = 2^31 - 1: the accumulators run at the edge of int32. Runs windows at
  // the start, the middle and the end (seek() is checked against a
  // continuous run below), each event against the definition.
  const int32_t big = 2147483647;
  const int32_t d[4] = {big, -3, 1000, -65537};
  am::LineDda<4> dda;
  ASSERT_TRUE(dda.start(d));
  ASSERT_EQ(dda.events(), uint32_t(big));
  const uint64_t big_n = uint32_t(big);
  for (uint64_t window : {uint64_t(0), big_n / 2 - 50000, big_n - 200000}) {
    dda.seek(uint32_t(window));
    int64_t pos[4];
    for (int i = 0; i < 4; ++i) pos[i] = nearest_position(window, uint64_t(std::llabs(d[i])), big_n);
    const uint64_t last = std::min(big_n, window + 200000);
    for (uint64_t e = window + 1; e <= last; ++e) {
      const am::StepEvent ev = dda.next();
      for (int i = 0; i < 4; ++i) {
        if (ev.axes & (1u << i)) ++pos[i];
        ASSERT_EQ(pos[i], nearest_position(e, uint64_t(std::llabs(d[i])), big_n)) << i << " " << e;
      }
    }
    if (last == big_n) {
      EXPECT_TRUE(dda.finished());
      for (int i = 0; i < 4; ++i) EXPECT_EQ(pos[i], std::llabs(d[i]));
    }
  }
}

TEST(MotionLineBresenham, LongBlockRunsContinuouslyToItsTarget) {
  // 2^26 events without seek(): the end is reached by stepping alone.
  const int32_t d[3] = {-(1 << 26), 12345, (1 << 26) - 1};
  am::LineDda<3> dda;
  ASSERT_TRUE(dda.start(d));
  int64_t pos[3] = {0, 0, 0};
  while (!dda.finished()) {
    const am::StepEvent ev = dda.next();
    for (int i = 0; i < 3; ++i)
      if (ev.axes & (1u << i)) pos[i] += (ev.dirs & (1u << i)) ? 1 : -1;
  }
  for (int i = 0; i < 3; ++i) EXPECT_EQ(pos[i], d[i]);
}

TEST(MotionLineBresenham, SeekMatchesAContinuousRun) {
  std::mt19937 rng(99);
  for (int trial = 0; trial < 50; ++trial) {
    const int32_t d[2] = {int32_t(rng() % 5000) - 2500, int32_t(rng() % 5000) - 2500};
    am::LineDda<2> run, sought;
    ASSERT_TRUE(run.start(d));
    ASSERT_TRUE(sought.start(d));
    const uint32_t at = run.events() ? rng() % run.events() : 0;
    for (uint32_t e = 0; e < at; ++e) run.next();
    sought.seek(at);
    ASSERT_EQ(sought.remaining(), run.remaining());
    while (!run.finished()) {
      const am::StepEvent a = run.next(), b = sought.next();
      ASSERT_EQ(a.axes, b.axes);
      ASSERT_EQ(a.dirs, b.dirs);
    }
    EXPECT_TRUE(sought.finished());
  }
}

}  // namespace

TEST(MotionLineBresenham, StepsAfterCountsWhatTheEventsMade) {
  // steps_after(i, e) against the steps next() actually gave, at every
  // event, for random blocks in both phases and over outside clocks.
  std::mt19937 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    const int32_t d[3] = {int32_t(rng() % 3001) - 1500, int32_t(rng() % 3001) - 1500, int32_t(rng() % 41) - 20};
    uint32_t dominant = 0;
    for (int32_t v : d) dominant = std::max<uint32_t>(dominant, uint32_t(std::abs(v)));
    const uint32_t events = trial % 3 == 0 ? 0 : dominant + rng() % 4000;
    const am::DdaPhase phase = trial % 2 ? am::DdaPhase::late : am::DdaPhase::nearest;
    am::LineDda<3> dda;
    ASSERT_TRUE(dda.start(d, events, phase));
    uint32_t made[3] = {0, 0, 0};
    for (uint32_t e = 0;; ++e) {
      for (uint8_t i = 0; i < 3; ++i) ASSERT_EQ(dda.steps_after(i, e), made[i]) << trial << " axis " << int(i) << " e " << e;
      if (dda.finished()) break;
      const am::StepEvent ev = dda.next();
      for (uint8_t i = 0; i < 3; ++i) made[i] += (ev.axes >> i) & 1u;
    }
    for (uint8_t i = 0; i < 3; ++i) EXPECT_EQ(made[i], uint32_t(std::abs(d[i])));
  }
}
