// core/lathe/follower.h: the leadscrew count after every run of spindle
// counts equals floor(lambda (s - phi)) of the exact rational, computed here
// independently in 128 bits from the physical definition, for every table
// entry on the seed's servo leadscrew and on stepper leadscrews, forward and
// through reversals; multi-start phases; the 32-bit limits.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "core/lathe/follower.h"
#include "core/lathe/pitch_tables.h"
#include "core/lathe/ratio.h"

namespace {

using i128 = __int128;

i128 floor_div(i128 a, i128 b) {  // b > 0
  const i128 q = a / b;
  return (a % b != 0 && a < 0) ? q - 1 : q;
}

// lambda (s - phi) with phi = phase_num / phase_den, floored; sign -1 for a
// reversed follower. lambda = num / den unreduced.
int64_t expected(i128 num, i128 den, int64_t s, i128 phase_num, i128 phase_den, int sign) {
  const i128 x = (i128(s) * phase_den - phase_num) * num * sign;
  return int64_t(floor_div(x, den * phase_den));
}

struct Raw {
  i128 num, den;
};
Raw raw_lambda(const am::Machine& m, const am::ThreadRequest& t) {
  return {i128(t.pitch.num) * t.starts * m.leadscrew.den * m.leadscrew_counts.num,
          i128(t.pitch.den) * m.leadscrew.num * m.leadscrew_counts.den * m.spindle_counts};
}

const am::Machine kSeed = {am::pitch_um(3175), am::servo_counts(30, 26), 40, false};
const am::Machine kStepper2mm = {am::pitch_um(2000), am::stepper_counts(200, 8), 4096, false};
const am::Machine kStepper12Tpi = {am::pitch_tpi(12), am::stepper_counts(200, 8), 40, false};

std::vector<am::Pitch> every_table_pitch() {
  std::vector<am::Pitch> v;
  for (const auto& t : am::kIsoCoarse) v.push_back(am::pitch_um(t.pitch_um));
  for (const auto& t : am::kIsoFine) v.push_back(am::pitch_um(t.pitch_um));
  for (const auto& t : am::kUnc) v.push_back(am::pitch_tpi_x2(t.tpi_x2));
  for (const auto& t : am::kUnf) v.push_back(am::pitch_tpi_x2(t.tpi_x2));
  for (uint8_t t : am::kCommonTpi) v.push_back(am::pitch_tpi_x2(t));
  for (uint16_t f : am::kTurningFeeds) v.push_back(am::pitch_um(f));
  return v;
}

// Drives the follower through `moves` (signed runs of spindle counts) and
// compares with the reference at the end of every run and, for the first
// `dense` counts, after every single count. Returns the final spindle count.
int64_t drive(am::Follower& f, const std::vector<int32_t>& moves, const Raw& r, i128 pn, i128 pd, int sign,
              int64_t dense, const std::string& what) {
  int64_t s = 0;
  for (int32_t run : moves) {
    const bool fwd = run > 0;
    for (int32_t k = 0; k < (fwd ? run : -run); ++k) {
      const int32_t before = f.position(), ahead = f.next_delta(fwd);
      f.edge(fwd);
      s += fwd ? 1 : -1;
      if (int32_t(uint32_t(f.position()) - uint32_t(before)) != ahead) {
        ADD_FAILURE() << what << ": next_delta() at s=" << s << " said " << ahead;
        return s;
      }
      if (s < dense && s > -dense && f.position() != expected(r.num, r.den, s, pn, pd, sign)) {
        ADD_FAILURE() << what << " at s=" << s;
        return s;
      }
    }
    if (f.position() != expected(r.num, r.den, s, pn, pd, sign)) {
      ADD_FAILURE() << what << " at s=" << s << ": " << f.position() << " vs "
                    << expected(r.num, r.den, s, pn, pd, sign);
      return s;
    }
  }
  return s;
}

std::vector<int32_t> forward_million() { return std::vector<int32_t>(1000, 1000); }

// 10^6 spindle counts in runs of 1..4000 forward and 1..3000 back, starting
// with a reversal through zero, so s goes negative too.
std::vector<int32_t> with_reversals(uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<int32_t> v = {-1500, 1};
  int64_t total = 1501;
  while (total < 1000000) {
    const int32_t run = (v.size() % 2 == 0) ? -int32_t(1 + rng() % 3000) : int32_t(1 + rng() % 4000);
    v.push_back(run);
    total += run < 0 ? -run : run;
  }
  return v;
}

TEST(LatheFollower, ZeroDriftOverAMillionCountsForEveryTableEntry) {
  const am::Machine machines[] = {kSeed, kStepper2mm, kStepper12Tpi};
  const char* names[] = {"seed servo 3.175 mm", "stepper 1600/2 mm, spindle 4096",
                         "stepper 1600/12 TPI, spindle 40"};
  const std::vector<am::Pitch> pitches = every_table_pitch();
  const std::vector<int32_t> fwd = forward_million();
  int checked = 0;
  for (int mi = 0; mi < 3; ++mi)
    for (size_t pi = 0; pi < pitches.size(); ++pi)
      for (am::Hand hand : {am::Hand::right, am::Hand::left}) {
        const am::ThreadRequest req = {pitches[pi], 1, hand};
        const am::GearRatio g = am::gear_ratio(machines[mi], req);
        ASSERT_EQ(g.status, am::RatioStatus::exact);
        const Raw r = raw_lambda(machines[mi], req);
        const int sign = hand == am::Hand::left ? -1 : 1;
        const std::string what = std::string(names[mi]) + " entry " + std::to_string(pi) +
                                 (sign < 0 ? " left" : " right");
        am::Follower f;
        ASSERT_TRUE(f.reset(g.ratio, g.reversed));
        EXPECT_EQ(drive(f, fwd, r, 0, 1, sign, 5000, what + " forward"), 1000000);
        ASSERT_TRUE(f.reset(g.ratio, g.reversed));
        drive(f, with_reversals(uint32_t(pi * 7 + mi)), r, 0, 1, sign, 5000, what + " reversals");
        ++checked;
      }
  EXPECT_EQ(checked, 3 * 2 * int(pitches.size()));
}

TEST(LatheFollower, RatiosAboveOneAndAtTheWidthLimit) {
  struct Case {
    uint32_t num, den;
  };
  const Case cases[] = {
      {39, 1},                               // 4 TPI on the seed: 39 counts per spindle count
      {1950, 127},                           // 2.5 mm on the seed
      {0xFFFFFFFFu, 1},                      // the largest whole step
      {0xFFFFFFFFu, am::kMaxDen},            // largest denominator, fraction near 1
      {am::kMaxDen + 1, am::kMaxDen},        // fraction 1 / 2^31
      {am::kMaxDen - 1, am::kMaxDen},        // fraction 1 - 2^-31
      {1, am::kMaxDen},                      // tiny lambda
      {3221225470u, 2147483647u},            // odd denominator below the limit
  };
  for (const Case& c : cases) {
    am::Follower f;
    ASSERT_TRUE(f.reset({c.num, c.den}, false)) << c.num << "/" << c.den;
    // Positions wrap modulo 2^32; compare in that ring.
    int64_t s = 0;
    std::mt19937 rng(c.num ^ c.den);
    for (int run = 0; run < 400; ++run) {
      const int32_t n = int32_t(1 + rng() % 5000) * ((run % 3 == 1) ? -1 : 1);
      for (int32_t k = 0; k < (n > 0 ? n : -n); ++k) f.edge(n > 0);
      s += n;
      const int64_t ref = expected(c.num, c.den, s, 0, 1, 1);
      ASSERT_EQ(uint32_t(f.position()), uint32_t(uint64_t(ref))) << c.num << "/" << c.den << " s=" << s;
      ASSERT_LT(f.residual(), f.denominator());
    }
  }
  // A denominator above 2^31 is refused.
  am::Follower f;
  EXPECT_FALSE(f.reset({1, am::kMaxDen + 1}, false));
  EXPECT_FALSE(f.reset({1, 0}, false));
}

// Start k of n on a 40-count spindle: phi = 40 k / n, an integer for 2, 4,
// 5 and 8 starts, not for 3, 6 or 7: the follower then works in 1/n of its
// unit and the position is still exactly floor(lambda (s - phi)).
TEST(LatheFollower, MultiStartPhasesAreExact) {
  for (uint8_t n = 1; n <= 8; ++n)
    for (uint8_t k = 0; k < n; ++k) {
      const am::ThreadRequest req = {am::pitch_um(1500), n, am::Hand::right};  // lead 1.5 n mm
      const am::GearRatio g = am::gear_ratio(kSeed, req);
      ASSERT_EQ(g.status, am::RatioStatus::exact);
      const am::Phase ph = am::start_phase(k, n, kSeed.spindle_counts);
      // The phase itself, independently: 40 k / n.
      ASSERT_EQ(i128(ph.num) * n, i128(40) * k * ph.den);
      am::Follower f;
      ASSERT_TRUE(f.reset(g.ratio, g.reversed, ph));
      const Raw r = raw_lambda(kSeed, req);
      drive(f, with_reversals(1000 + n * 8 + k), r, i128(40) * k, n, 1,
            20000, "starts " + std::to_string(n) + " k " + std::to_string(k));
    }
  // The offset between neighbouring starts is one pitch of carriage travel:
  // after the same spindle travel, start k+1 trails start k by lambda 40 / n
  // counts (within the one count of flooring).
  const am::ThreadRequest three = {am::pitch_um(1500), 3, am::Hand::right};
  const am::GearRatio g = am::gear_ratio(kSeed, three);
  am::Follower f0, f1;
  ASSERT_TRUE(f0.reset(g.ratio, false, am::start_phase(0, 3, 40)));
  ASSERT_TRUE(f1.reset(g.ratio, false, am::start_phase(1, 3, 40)));
  EXPECT_EQ(f1.denominator(), f0.denominator() * 3);
  for (int i = 0; i < 400; ++i) f0.advance(), f1.advance();  // ten turns
  // One pitch = 1500 um at 3175/780 um per count = 368.5 counts.
  const int64_t gap = f0.position() - f1.position();
  EXPECT_GE(gap, 368);
  EXPECT_LE(gap, 369);
}

TEST(LatheFollower, ReversedFollowerMirrorsThePosition) {
  // reversed: floor(-lambda s), i.e. -ceil(lambda s).
  am::Follower f;
  ASSERT_TRUE(f.reset({780, 127}, true));
  for (int i = 0; i < 127; ++i) f.edge(true);
  EXPECT_EQ(f.position(), -780);
  f.edge(true);
  EXPECT_EQ(f.position(), -787);  // -ceil(128 x 780 / 127) = -ceil(786.14)
  f.edge(false);
  EXPECT_EQ(f.position(), -780);
}

}  // namespace
