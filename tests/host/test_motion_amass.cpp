// The smoothing of core/motion/amass.h: its level against the rule written
// out here, the scaled block against float multiplication, and a refined
// interpolator against the k-th step of every axis on event
// ceil(k N 2^L / n), computed here from that formula.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "core/motion/amass.h"
#include "core/motion/line_dda.h"

namespace {

// The rule, by brute force over the levels.
uint8_t expected_level(uint32_t events, uint32_t cruise, uint32_t cap) {
  uint8_t best = 0;
  for (uint8_t l = 1; l <= 3; ++l)
    if (uint64_t(cruise) << l <= cap && uint64_t(events) << l <= (uint64_t(1) << 24)) best = l;
  return best;
}

TEST(Amass, LevelIsTheFinestThatKeepsWithinTheEventCapAndTheTrapezoidsCount) {
  const uint32_t caps[] = {20000, 10000, 5000, 7, 1};
  const uint32_t cruises[] = {0, 1, 2, 624, 625, 1249, 1250, 1251, 2499, 2500, 2501, 4999, 5000, 5001,
                              9999, 10000, 10001, 20000, 40000, 160000, 0xFFFFFFFFu};
  const uint32_t events[] = {1, 1000, (1u << 21) - 1, 1u << 21, (1u << 21) + 1, 1u << 22, (1u << 23) + 1,
                             1u << 24, 0x7FFFFFFFu};
  int levels_seen[4] = {};
  for (uint32_t cap : caps)
    for (uint32_t c : cruises)
      for (uint32_t e : events) {
        const uint8_t l = am::amass::level(e, c, cap);
        EXPECT_EQ(l, expected_level(e, c, cap)) << "events " << e << " cruise " << c << " cap " << cap;
        ++levels_seen[l];
      }
  for (int l = 0; l < 4; ++l) EXPECT_GT(levels_seen[l], 0) << "level " << l << " never chosen";
}

TEST(Amass, ScaleMultipliesEveryFigureByTwoToTheLevel) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> speed(0.001f, 2.0e5f);
  for (int n = 0; n < 20000; ++n) {
    const uint8_t l = uint8_t(n % 4);
    am::TrapezoidBlock b{uint32_t(rng() % (1u << 21)) + 1, n % 5 ? speed(rng) : 0.0f, speed(rng),
                         n % 3 ? speed(rng) : 0.0f, speed(rng) * 100};
    const am::TrapezoidBlock before = b;
    am::amass::scale(b, l);
    const float k = float(1u << l);
    EXPECT_EQ(b.events, before.events << l);
    EXPECT_EQ(b.entry, before.entry * k);
    EXPECT_EQ(b.cruise, before.cruise * k);
    EXPECT_EQ(b.exit, before.exit * k);
    EXPECT_EQ(b.accel, before.accel * k);
  }
}

// Events (1-based) at which each axis steps.
std::vector<std::vector<uint32_t>> pulses(am::LineDda<4>& dda) {
  std::vector<std::vector<uint32_t>> out(4);
  for (uint32_t e = 1; !dda.finished(); ++e) {
    const am::StepEvent ev = dda.next();
    for (uint8_t i = 0; i < 4; ++i)
      if (ev.axes & (1u << i)) out[i].push_back(e);
  }
  return out;
}

TEST(Amass, ARefinedBlockStepsEveryAxisAtTheFirstEventAfterItsLineCrossesAStep) {
  std::mt19937 rng(11);
  int blocks = 0;
  for (int n = 0; n < 3000; ++n) {
    int32_t delta[4];
    uint32_t dominant = 0;
    for (int32_t& d : delta) {
      const uint32_t span = n % 3 == 0 ? 5u : n % 3 == 1 ? 200u : 3000u;
      d = rng() % 4 == 0 ? 0 : int32_t(rng() % span) - int32_t(span / 2);
      dominant = std::max(dominant, uint32_t(std::abs(d)));
    }
    if (dominant == 0) continue;
    const uint8_t l = uint8_t(1 + n % 3);
    am::LineDda<4> dda;
    ASSERT_TRUE(dda.start(delta, l));
    const uint32_t events = dominant << l;
    ASSERT_EQ(dda.events(), events);
    uint8_t dirs = 0;
    for (uint8_t i = 0; i < 4; ++i) dirs |= uint8_t(delta[i] > 0 ? 1u << i : 0u);
    EXPECT_EQ(dda.dirs(), dirs);
    const std::vector<std::vector<uint32_t>> got = pulses(dda);
    for (uint8_t i = 0; i < 4; ++i) {
      const uint64_t steps = uint64_t(std::abs(delta[i]));
      ASSERT_EQ(got[i].size(), steps) << "axis " << int(i);
      for (uint64_t k = 1; k <= steps; ++k) {
        const uint64_t due = (k * events + steps - 1) / steps;  // ceil(k N 2^L / n)
        ASSERT_EQ(got[i][k - 1], due) << "axis " << int(i) << " step " << k;
        // The closed form the odometer counts with agrees at every step.
        EXPECT_EQ(dda.steps_after(i, uint32_t(due)), k);
        EXPECT_EQ(dda.steps_after(i, uint32_t(due - 1)), k - 1);
      }
      // The dominant axis exactly on every 2^L-th event.
      if (steps == dominant) {
        for (uint64_t k = 1; k <= steps; ++k) EXPECT_EQ(got[i][k - 1], k << l);
      }
    }
    ++blocks;
  }
  EXPECT_GT(blocks, 2500);
}

}  // namespace
