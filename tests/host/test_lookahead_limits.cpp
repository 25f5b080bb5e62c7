// Lookahead (core/motion/lookahead.h) at the edges of its input range. What is
// refused (nothing queued): INT32_MIN steps or lengths (out_of_range), lengths
// derived from steps beyond int32 (out_of_range), a feed <= 0 on a G1
// (bad_feed). What is clamped: feeds to the axes' rates and to 2^28 - 1 lu/s
// (26.8 m/s) along the path, tiny feeds up to 1 event/s, axis settings to
// their documented ranges, path accelerations to 2^31 - 1 lu/s^2, squared
// speeds to 2^58. Whatever the input, nothing wraps: checked against double
// references here and by invariants over a random sweep of extreme inputs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

#include "core/motion/lookahead.h"

namespace {

constexpr int32_t kMax = 0x7FFFFFFF;
constexpr int32_t kMin = -0x7FFFFFFF - 1;

const am::LookaheadAxis kAxes[4] = {{100000, 20000, 100000}, {100000, 20000, 100000}, {80000, 16000, 50000},
                                    {93000, 5580, 27900}};

// The invariants every planned block keeps, whatever went in.
template <uint8_t N, uint8_t Size>
void expect_sane(const am::Lookahead<N, Size>& p, const am::LookaheadAxis (&axes)[N]) {
  for (uint8_t i = 0; i < p.size(); ++i) {
    am::LookaheadMove<N> m;
    p.move(i, m);
    const auto& b = p.block(i);
    EXPECT_GE(m.nominal, 1u);
    EXPECT_GE(m.accel, 1u);
    EXPECT_LE(m.entry, m.nominal);
    EXPECT_LE(m.exit, m.nominal);
    EXPECT_LE(m.cruise, m.nominal);
    EXPECT_GE(m.cruise, std::max(m.entry, m.exit));
    // Exactly feasible: |entry^2 - exit^2| <= 2 accel events.
    const unsigned __int128 e2 = uint64_t(m.entry) * m.entry, x2 = uint64_t(m.exit) * m.exit;
    const unsigned __int128 room = 2 * (unsigned __int128)(m.accel) * m.events;
    EXPECT_TRUE(e2 <= x2 + room && x2 <= e2 + room) << "block " << int(i) << " infeasible";
    EXPECT_GE(b.length, 1u);
    for (uint8_t k = 0; k < N; ++k) {
      const uint64_t s = uint64_t(std::llabs(int64_t(m.steps[k])));
      const uint32_t rate = std::min<uint32_t>(std::max<uint32_t>(axes[k].max_rate, 1), am::kLookaheadMaxRate);
      const uint32_t accel = std::min<uint32_t>(std::max<uint32_t>(axes[k].max_accel, 1), am::kLookaheadMaxAccel);
      EXPECT_LE(uint64_t(m.nominal) * s, uint64_t(rate) * m.events) << "axis " << int(k);
      EXPECT_LE(uint64_t(m.accel) * s, uint64_t(accel) * m.events) << "axis " << int(k);
    }
    // Along the path: at most 2^28 - 1 lu/s (to the rounding of events/s).
    EXPECT_LE(double(m.nominal) - 1, double(am::kLookaheadMaxSpeed) * m.events / b.length);
    EXPECT_LE(b.entry_sqr.value(), b.max_entry_sqr.value());
    EXPECT_LE(b.max_entry_sqr.value(), uint64_t(am::kLookaheadMaxSpeed) * am::kLookaheadMaxSpeed);
    EXPECT_LE(b.delta_sqr.value(), am::kLookaheadMaxSqr);
    EXPECT_GE(b.delta_sqr.value(), 2u);
  }
  if (!p.empty()) {
    EXPECT_EQ(p.exit_sqr(uint8_t(p.size() - 1)), 0u);
  }
}

}  // namespace

TEST(LookaheadLimits, RefusedInputsQueueNothing) {
  am::Lookahead<4, 4> p(kAxes);
  const int32_t ok[4] = {100, 0, 0, 0}, ok_len[4] = {10000, 0, 0, 0};
  const int32_t min_step[4] = {100, kMin, 0, 0}, min_len[4] = {10000, kMin, 0, 0};
  EXPECT_EQ(p.add(min_step, ok_len, 10000000, false), am::LookaheadStatus::out_of_range);
  EXPECT_EQ(p.add(ok, min_len, 10000000, false), am::LookaheadStatus::out_of_range);
  EXPECT_EQ(p.add_steps(min_step, 10000000, false), am::LookaheadStatus::out_of_range);
  EXPECT_EQ(p.add(ok, ok_len, 0, false), am::LookaheadStatus::bad_feed);
  EXPECT_EQ(p.add(ok, ok_len, -5, false), am::LookaheadStatus::bad_feed);
  const int32_t none[4] = {0, 0, 0, 0};
  EXPECT_EQ(p.add(none, ok_len, 10000000, false), am::LookaheadStatus::empty);  // moves less than a step
  EXPECT_EQ(p.size(), 0u);
  // A rapid ignores its feed.
  EXPECT_EQ(p.add(ok, ok_len, 0, true), am::LookaheadStatus::queued);
  EXPECT_EQ(p.add(ok, ok_len, -5, true), am::LookaheadStatus::queued);
  EXPECT_EQ(p.add(ok, ok_len, 10000000, false), am::LookaheadStatus::queued);
  EXPECT_EQ(p.add(ok, ok_len, 10000000, false), am::LookaheadStatus::queued);
  EXPECT_EQ(p.add(ok, ok_len, 10000000, false), am::LookaheadStatus::full);
  EXPECT_EQ(p.size(), 4u);
  // Lengths derived from steps beyond int32: 2^31 - 1 steps of a 1 step/m
  // axis would be 2^31 m.
  const am::LookaheadAxis coarse[1] = {{1, 1000, 1000}};
  am::Lookahead<1, 2> q(coarse);
  const int32_t far[1] = {kMax};
  EXPECT_EQ(q.add_steps(far, 10000000, false), am::LookaheadStatus::out_of_range);
  EXPECT_EQ(q.size(), 0u);
}

TEST(LookaheadLimits, LargestStepsAndLengthsDoNotWrap) {
  // Every axis at 2^31 - 1 steps over 2^31 - 1 lu (214 m): the path is 2^32
  // - 2 lu, the largest the planner holds; then the same with lengths from
  // 2^31 - 1 steps along X only, then back.
  am::Lookahead<4, 4> p(kAxes);
  const int32_t all[4] = {kMax, kMax, kMax, kMax};
  ASSERT_EQ(p.add(all, all, kMax, false), am::LookaheadStatus::queued);
  const int32_t x[4] = {kMax, 0, 0, 0};
  ASSERT_EQ(p.add(x, x, kMax, false), am::LookaheadStatus::queued);
  const int32_t back[4] = {-kMax, -kMax, -kMax, -kMax};
  ASSERT_EQ(p.add(back, back, 1, false), am::LookaheadStatus::queued);
  expect_sane(p, kAxes);
  // The first block: length within 2^-23 of 2 (2^31 - 1), rates from the
  // slowest axis per event (E: 5580 steps/s with as many steps as X).
  const double length = 2.0 * kMax;
  EXPECT_LE(p.block(0).length, length);
  EXPECT_GE(p.block(0).length, length * (1 - 1.0 / (1 << 23)));
  am::LookaheadMove<4> m;
  p.move(0, m);
  EXPECT_EQ(m.events, uint32_t(kMax));
  EXPECT_EQ(m.nominal, 5580u);
  EXPECT_EQ(m.accel, 27900u);
  // 2 a L = 2 * (27900 * L / events) * L, far below the 2^58 saturation.
  const double two_al = 2 * std::floor(27900.0 * p.block(0).length / kMax) * p.block(0).length;
  EXPECT_NEAR(double(p.block(0).delta_sqr.value()), two_al, two_al * 1e-9);
  // The triangle's peak of a rest-to-rest block: sqrt(a events) capped by
  // nominal.
  EXPECT_EQ(m.cruise, m.nominal);
  // The third block's feed of 1/10000 mm/min is clamped up to 1 event/s.
  p.move(2, m);
  EXPECT_EQ(m.nominal, 1u);
  // Its junction (120 degrees after the X block) is capped by that feed's
  // path speed, floored at 1 lu/s; the junction into X is finite.
  EXPECT_EQ(p.block(2).max_entry_sqr.value(), 1u);
  EXPECT_GT(p.block(1).max_entry_sqr.value(), 1u);
  EXPECT_LT(p.block(1).max_entry_sqr.value(), uint64_t(40000) * 40000);
}

TEST(LookaheadLimits, HugeAndTinyFeeds) {
  am::Lookahead<4, 4> p(kAxes);
  const int32_t steps[4] = {1000, 0, 0, 0}, len[4] = {100000, 0, 0, 0};  // 10 mm of X
  ASSERT_EQ(p.add(steps, len, kMax, false), am::LookaheadStatus::queued);
  am::LookaheadMove<4> m;
  p.move(0, m);
  EXPECT_EQ(m.nominal, 20000u);  // clamped to X's rate
  am::Lookahead<4, 4> q(kAxes);
  ASSERT_EQ(q.add(steps, len, 1, false), am::LookaheadStatus::queued);  // 0.0001 mm/min
  q.move(0, m);
  EXPECT_EQ(m.nominal, 1u);  // 1 event/s, the floor
  // 600 lu/min = 10 lu/s = 0.001 mm/s: still 1 event/s (0.01 mm/step here).
  am::Lookahead<4, 4> r(kAxes);
  ASSERT_EQ(r.add(steps, len, 600, false), am::LookaheadStatus::queued);
  r.move(0, m);
  EXPECT_EQ(m.nominal, 1u);
  expect_sane(p, kAxes);
  expect_sane(q, kAxes);
  expect_sane(r, kAxes);
}

TEST(LookaheadLimits, AxisSettingsAreClampedAndPathSpeedIsCapped) {
  // 1 step per metre at 2^24 - 1 steps/s would be 16 million m/s: the path
  // cap of 2^28 - 1 lu/s takes over. Rates and accelerations of 0 or 2^32 - 1
  // are clamped to 1 and to their tops.
  const am::LookaheadAxis wild[3] = {{1, 0xFFFFFFFFu, 0xFFFFFFFFu}, {0, 0, 0}, {0xFFFFFFFFu, 0xFFFFFFFFu, 1}};
  am::Lookahead<3, 4> p(wild, 0xFFFFFFFFu);
  const int32_t x[3] = {3, 0, 0}, xl[3] = {30000000, 0, 0};  // 3 m in 3 steps
  ASSERT_EQ(p.add(x, xl, 0, true), am::LookaheadStatus::queued);
  am::LookaheadMove<3> m;
  p.move(0, m);
  EXPECT_EQ(m.nominal, uint32_t(uint64_t(am::kLookaheadMaxSpeed) * 3 / 30000000));  // 26 events/s
  EXPECT_EQ(m.accel, am::kLookaheadMaxAccel);
  const int32_t y[3] = {0, 7, 0}, yl[3] = {0, 1000, 0};
  ASSERT_EQ(p.add(y, yl, 0, true), am::LookaheadStatus::queued);
  p.move(1, m);
  EXPECT_EQ(m.nominal, 1u);  // rate 0 -> 1 step/s
  EXPECT_EQ(m.accel, 1u);
  const int32_t z[3] = {0, 0, kMax};
  ASSERT_EQ(p.add_steps(z, 10000000, false), am::LookaheadStatus::queued);  // 0.5 m from steps
  p.move(2, m);
  EXPECT_EQ(m.accel, 1u);
  EXPECT_NEAR(double(p.block(2).length), double(kMax) * 1e7 / 0xFFFFFFFFu, 1.0);
  const am::LookaheadAxis clamped[3] = {{1, am::kLookaheadMaxRate, am::kLookaheadMaxAccel}, {1, 1, 1},
                                        {0xFFFFFFFFu, am::kLookaheadMaxRate, 1}};
  expect_sane(p, clamped);
}

TEST(LookaheadLimits, RandomExtremeInputsKeepEveryInvariant) {
  std::mt19937 rng(2024);
  auto log_uniform = [&](double lo, double hi) {
    return std::exp(std::uniform_real_distribution<double>(std::log(lo), std::log(hi))(rng));
  };
  int queued = 0;
  for (int run = 0; run < 60; ++run) {
    am::LookaheadAxis axes[4];
    for (auto& a : axes) {
      a.steps_per_m = uint32_t(log_uniform(1, 4e9));
      a.max_rate = uint32_t(log_uniform(1, 4e9));
      a.max_accel = uint32_t(log_uniform(1, 4e9));
    }
    am::LookaheadAxis clamped[4];
    for (int i = 0; i < 4; ++i) {
      clamped[i] = axes[i];
      clamped[i].max_rate = std::min<uint32_t>(std::max<uint32_t>(axes[i].max_rate, 1), am::kLookaheadMaxRate);
      clamped[i].max_accel = std::min<uint32_t>(std::max<uint32_t>(axes[i].max_accel, 1), am::kLookaheadMaxAccel);
    }
    am::Lookahead<4, 6> p(axes, uint32_t(log_uniform(1, 2e5)));
    for (int k = 0; k < 40; ++k) {
      int32_t steps[4], len[4];
      for (int i = 0; i < 4; ++i) {
        const int sign = std::uniform_int_distribution<int>(0, 1)(rng) ? 1 : -1;
        steps[i] = std::uniform_int_distribution<int>(0, 3)(rng) ? sign * int32_t(log_uniform(1, kMax)) : 0;
        len[i] = std::uniform_int_distribution<int>(0, 3)(rng) ? sign * int32_t(log_uniform(1, kMax)) : 0;
      }
      const bool rapid = std::uniform_int_distribution<int>(0, 4)(rng) == 0;
      const int32_t feed = int32_t(log_uniform(1, kMax));
      if (p.full()) {
        am::LookaheadMove<4> m;
        ASSERT_TRUE(p.begin(m));
        ASSERT_TRUE(p.lock(m));
        ASSERT_TRUE(p.finish());
      }
      const am::LookaheadStatus st = std::uniform_int_distribution<int>(0, 5)(rng)
                                         ? p.add(steps, len, feed, rapid)
                                         : p.add_steps(steps, feed, rapid);
      ASSERT_TRUE(st == am::LookaheadStatus::queued || st == am::LookaheadStatus::empty ||
                  st == am::LookaheadStatus::out_of_range);
      queued += st == am::LookaheadStatus::queued;
      expect_sane(p, clamped);
      if (::testing::Test::HasFailure()) return;
    }
  }
  EXPECT_GT(queued, 1500);
}

TEST(LookaheadLimits, FewerAxesAndTheSmallestRing) {
  const am::LookaheadAxis one[1] = {{80000, 20000, 80000}};
  am::Lookahead<1, 2> p(one);
  const int32_t s[1] = {800}, l[1] = {100000};
  ASSERT_EQ(p.add(s, l, 30000000, false), am::LookaheadStatus::queued);
  ASSERT_EQ(p.add(s, l, 30000000, false), am::LookaheadStatus::queued);
  EXPECT_EQ(p.add(s, l, 30000000, false), am::LookaheadStatus::full);
  am::LookaheadMove<1> m;
  p.move(0, m);
  EXPECT_EQ(m.exit, 4000u);  // straight on at 50 mm/s, 80 steps/mm
  EXPECT_TRUE(m.final);
  expect_sane(p, one);
  static_assert(sizeof(am::LookaheadBlock<4>) >= 53, "the documented block size is a lower bound on the host");
}
