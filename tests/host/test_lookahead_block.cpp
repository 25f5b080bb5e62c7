// Lookahead (core/motion/lookahead.h), one block at a time: its nominal speed
// and acceleration in events/s against a double-precision reference built
// here from the definitions (feed along the path converted with the path
// length, every axis held to its rate and acceleration, the limiting axis
// deciding), over a sweep of directions on axes with unequal steps/mm, rates
// and accelerations; and the profile the step generator gets for a lone
// block (starts and ends at rest, a triangle when too short to cruise).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/motion/lookahead.h"

namespace {

// X 80 steps/mm, 300 mm/s, 2000 mm/s^2; Y 100 steps/mm, 200 mm/s, 500 mm/s^2;
// Z 400 steps/mm, 10 mm/s, 100 mm/s^2; E 93 steps/mm, 60 mm/s, 300 mm/s^2.
const am::LookaheadAxis kAxes[4] = {
    {80000, 24000, 160000}, {100000, 20000, 50000}, {400000, 4000, 40000}, {93000, 5580, 27900}};

struct Reference {
  uint32_t events = 0;
  double length = 0;       // lu
  double nominal = 0;      // events/s
  double accel = 0;        // events/s^2
  int rate_axis = -1;      // axis that limits the speed, -1: the feed
  int accel_axis = -1;
};

// steps_i = round(length_i * steps/m / 10^7): what the interpreter's targets give.
void make_move(const double (&dir)[4], double mm, int32_t (&steps)[4], int32_t (&len)[4]) {
  for (int i = 0; i < 4; ++i) {
    len[i] = int32_t(std::lround(dir[i] * mm * 10000.0));
    steps[i] = int32_t(std::lround(len[i] * double(kAxes[i].steps_per_m) / 1e7));
  }
}

Reference reference(const int32_t (&steps)[4], const int32_t (&len)[4], double feed, bool rapid) {
  Reference r;
  double sum = 0;
  for (int i = 0; i < 4; ++i) {
    r.events = std::max<uint32_t>(r.events, uint32_t(std::abs(steps[i])));
    sum += double(len[i]) * len[i];
  }
  r.length = std::sqrt(sum);
  r.nominal = rapid ? 1e300 : feed / 60.0 * r.events / r.length;
  r.accel = 1e300;
  for (int i = 0; i < 4; ++i) {
    if (steps[i] == 0) continue;
    const double cap = double(kAxes[i].max_rate) * r.events / std::abs(steps[i]);
    if (cap < r.nominal) {
      r.nominal = cap;
      r.rate_axis = i;
    }
    const double acap = double(kAxes[i].max_accel) * r.events / std::abs(steps[i]);
    if (acap < r.accel) {
      r.accel = acap;
      r.accel_axis = i;
    }
  }
  return r;
}

// Directions over the sphere, E riding along on some.
std::vector<std::vector<double>> directions() {
  std::vector<std::vector<double>> out;
  for (int el = -75; el <= 75; el += 25) {
    for (int az = 0; az < 360; az += 15) {
      const double a = az * M_PI / 180, e = el * M_PI / 180;
      out.push_back({std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e), 0.0});
      out.push_back({std::cos(e) * std::cos(a) * 0.8, std::cos(e) * std::sin(a) * 0.8, std::sin(e) * 0.8, 0.6});
    }
  }
  return out;
}

}  // namespace

TEST(LookaheadBlock, NominalAndAccelerationComeFromTheLimitingAxisOrTheFeed) {
  int axis_limited = 0, feed_limited = 0;
  int rate_axes_seen[4] = {0, 0, 0, 0}, accel_axes_seen[4] = {0, 0, 0, 0};
  for (const auto& d : directions()) {
    const double dir[4] = {d[0], d[1], d[2], d[3]};
    for (double mm : {0.1, 2.5, 60.0}) {
      for (double feed_mm_min : {10.0, 600.0, 3000.0, 20000.0, -1.0}) {
        const bool rapid = feed_mm_min < 0;
        const int32_t feed = rapid ? 0 : int32_t(feed_mm_min * 10000);
        int32_t steps[4], len[4];
        make_move(dir, mm, steps, len);
        am::Lookahead<4, 4> p(kAxes);
        ASSERT_EQ(p.add(steps, len, feed, rapid), am::LookaheadStatus::queued);
        const Reference r = reference(steps, len, feed, rapid);
        am::LookaheadMove<4> m;
        p.move(0, m);
        ASSERT_EQ(m.events, r.events);
        EXPECT_EQ(m.dominant, std::max_element(steps, steps + 4, [](int32_t a, int32_t b) {
                                return std::abs(a) < std::abs(b);
                              }) - steps);
        // No axis ever above its rate or acceleration (exact, in integers).
        for (int i = 0; i < 4; ++i) {
          const uint64_t s = uint64_t(std::abs(steps[i]));
          EXPECT_LE(uint64_t(m.nominal) * s, uint64_t(kAxes[i].max_rate) * m.events) << i;
          EXPECT_LE(uint64_t(m.accel) * s, uint64_t(kAxes[i].max_accel) * m.events) << i;
        }
        // The acceleration is the limiting axis's, to the event/s^2.
        EXPECT_EQ(m.accel, uint32_t(std::floor(r.accel))) << mm << " " << feed_mm_min;
        ++accel_axes_seen[r.accel_axis];
        if (r.rate_axis >= 0) {
          // Axis-limited: exactly floor(rate * events / |steps|).
          EXPECT_EQ(m.nominal, uint32_t(std::floor(r.nominal))) << mm << " " << feed_mm_min;
          ++axis_limited;
          ++rate_axes_seen[r.rate_axis];
        } else {
          // Feed-limited: the length is rounded down to the lu, so at most
          // nominal / length above the reference, and never 1 below it.
          EXPECT_GE(m.nominal + 1.0, r.nominal) << mm << " " << feed_mm_min;
          EXPECT_LE(m.nominal, r.nominal * (1 + 1.0 / (r.length - 1)) + 1e-9) << mm << " " << feed_mm_min;
          ++feed_limited;
        }
        // What the block can gain or shed, 2 a L in path units (a rounded
        // down in events/s^2 and in lu/s^2, L rounded down).
        const double a_path = r.accel * r.length / r.events;
        EXPECT_NEAR(double(p.block(0).delta_sqr.value()), 2 * a_path * r.length,
                    2 * a_path * r.length * (3.0 / r.length + 2.0 / a_path + 1.0 / r.accel));
      }
    }
  }
  // The sweep reaches every case it claims to test.
  EXPECT_GT(axis_limited, 100);
  EXPECT_GT(feed_limited, 100);
  for (int i = 0; i < 4; ++i) {
    EXPECT_GT(rate_axes_seen[i], 0) << "axis " << i << " never limited the rate";
    EXPECT_GT(accel_axes_seen[i], 0) << "axis " << i << " never limited the acceleration";
  }
}

TEST(LookaheadBlock, RapidsRunAtTheLimitingAxisRate) {
  // X alone: its own rate; X and Y together: whichever reaches its rate
  // first along the path (X 300 mm/s, Y 200 mm/s: at (0.8, 0.6) Y's 333
  // mm/s along the path beats X's 375); a Z component: Z's 10 mm/s holds
  // everything back.
  struct Case {
    double dir[4];
    int limiting;
  };
  const Case cases[] = {{{1, 0, 0, 0}, 0},        {{0, 1, 0, 0}, 1},     {{0.6, 0.8, 0, 0}, 1},
                        {{0.8, 0.6, 0, 0}, 1},      {{0.95, -0.31, 0, 0}, 0}, {{0.7, 0.7, 0.14, 0}, 2},
                        {{0, 0, -1, 0}, 2},         {{0, 0.3, 0, 0.95}, 3}};
  for (const Case& c : cases) {
    int32_t steps[4], len[4];
    make_move(c.dir, 25.0, steps, len);
    am::Lookahead<4, 4> p(kAxes);
    ASSERT_EQ(p.add(steps, len, 0, true), am::LookaheadStatus::queued);
    am::LookaheadMove<4> m;
    p.move(0, m);
    const uint64_t want = uint64_t(kAxes[c.limiting].max_rate) * m.events / uint32_t(std::abs(steps[c.limiting]));
    EXPECT_EQ(m.nominal, want) << c.dir[0] << " " << c.dir[1] << " " << c.dir[2];
  }
}

TEST(LookaheadBlock, ALoneBlockStartsAndEndsAtRest) {
  // Long enough to cruise: cruise = nominal. Too short: a triangle whose
  // peak is sqrt(a * events) (from rest to rest over the block).
  for (double mm : {0.05, 0.4, 3.0, 80.0}) {
    const double dir[4] = {0.6, 0.8, 0, 0};
    int32_t steps[4], len[4];
    make_move(dir, mm, steps, len);
    am::Lookahead<4, 4> p(kAxes);
    ASSERT_EQ(p.add(steps, len, 60000000, false), am::LookaheadStatus::queued);  // 6000 mm/min
    am::LookaheadMove<4> m;
    p.move(0, m);
    EXPECT_EQ(m.entry, 0u);
    EXPECT_EQ(m.exit, 0u);
    const double peak = std::sqrt(double(m.accel) * m.events);
    const double want = std::min<double>(m.nominal, peak);
    EXPECT_LE(m.cruise, want + 1e-9) << mm;
    EXPECT_GE(m.cruise, want * (1 - 1.0 / 32768) - 1) << mm;
    EXPECT_FALSE(m.final);  // the newest block may still be continued
    EXPECT_EQ(m.dirs, 3u);
    EXPECT_EQ(m.steps[0], steps[0]);
    EXPECT_EQ(m.steps[1], steps[1]);
  }
}

TEST(LookaheadBlock, DirectionBitsAndStepsAreTheBlocksOwn) {
  am::Lookahead<4, 4> p(kAxes);
  const int32_t steps[4] = {-80, 100, 0, -9};
  const int32_t len[4] = {-10000, 10000, 0, -968};
  ASSERT_EQ(p.add(steps, len, 30000000, false), am::LookaheadStatus::queued);
  am::LookaheadMove<4> m;
  p.move(0, m);
  EXPECT_EQ(m.dirs, 2u);  // only Y forward
  EXPECT_EQ(m.dominant, 1u);
  EXPECT_EQ(m.events, 100u);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(m.steps[i], steps[i]);
  EXPECT_EQ(p.block(0).length, 14175u);  // floor(sqrt(2 * 10000^2 + 968^2))
}

TEST(LookaheadBlock, LengthsFromStepsWhenTheProgramGivesNone) {
  // add_steps(): lengths from steps per metre, so the same move in steps
  // plans the same as with the program's lengths.
  const double dir[4] = {0.3, -0.9, 0.3, 0};
  int32_t steps[4], len[4];
  make_move(dir, 12.0, steps, len);
  am::Lookahead<4, 4> with_lengths(kAxes), from_steps(kAxes);
  ASSERT_EQ(with_lengths.add(steps, len, 20000000, false), am::LookaheadStatus::queued);
  ASSERT_EQ(from_steps.add_steps(steps, 20000000, false), am::LookaheadStatus::queued);
  am::LookaheadMove<4> a, b;
  with_lengths.move(0, a);
  from_steps.move(0, b);
  EXPECT_NEAR(double(from_steps.block(0).length), double(with_lengths.block(0).length), 30.0);
  EXPECT_NEAR(double(b.nominal), double(a.nominal), 0.005 * a.nominal);
  EXPECT_EQ(b.accel, a.accel);
}
