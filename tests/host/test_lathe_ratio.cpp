// core/lathe/ratio.h: exact reduced gear ratios against an independent
// 128-bit computation from the physical definition, the seed's figures, and
// the denominator-150 comparison (the seed's worst pitch error reproduced,
// ours measured).
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "core/lathe/pitch_tables.h"
#include "core/lathe/ratio.h"

namespace {

using u128 = unsigned __int128;
using i128 = __int128;

u128 to_native(const am::U128& x) {
  u128 v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 32) | x.w[i];
  return v;
}

u128 gcd(u128 a, u128 b) {
  while (b != 0) {
    const u128 t = a % b;
    a = b;
    b = t;
  }
  return a;
}

// lambda from the physical definition, unreduced:
// (pitch starts / leadscrew pitch) (leadscrew counts per turn / spindle counts).
struct Raw {
  u128 num, den;
};
Raw raw_lambda(const am::Machine& m, const am::ThreadRequest& t) {
  return {u128(t.pitch.num) * t.starts * m.leadscrew.den * m.leadscrew_counts.num,
          u128(t.pitch.den) * m.leadscrew.num * m.leadscrew_counts.den * m.spindle_counts};
}

const am::Machine kSeed = {am::pitch_um(3175), am::servo_counts(30, 26), 40, false};
const am::Machine kStepper2mm = {am::pitch_um(2000), am::stepper_counts(200, 8), 4096, false};
const am::Machine kStepper12Tpi = {am::pitch_tpi(12), am::stepper_counts(200, 8), 40, false};
// 16 microsteps through a 30:40 belt onto a 5 mm screw, 1000-count spindle,
// motor wired the other way round.
const am::Machine kStepperBelt = {am::pitch_um(5000), am::stepper_counts(200, 16, 30, 40), 1000, true};

struct Entry {
  std::string name;
  am::Pitch pitch;
};

std::vector<Entry> every_table_entry() {
  std::vector<Entry> v;
  for (const auto& t : am::kIsoCoarse)
    v.push_back({"M" + std::to_string(t.diameter_x10) + "/10 coarse", am::pitch_um(t.pitch_um)});
  for (const auto& t : am::kIsoFine)
    v.push_back({"M" + std::to_string(t.diameter_x10) + "/10 x " + std::to_string(t.pitch_um) + " um",
                 am::pitch_um(t.pitch_um)});
  for (const auto& t : am::kUnc)
    v.push_back({"UNC " + std::to_string(t.diameter_x10000), am::pitch_tpi_x2(t.tpi_x2)});
  for (const auto& t : am::kUnf)
    v.push_back({"UNF " + std::to_string(t.diameter_x10000), am::pitch_tpi_x2(t.tpi_x2)});
  for (uint8_t t : am::kCommonTpi) v.push_back({std::to_string(t) + "/2 TPI", am::pitch_tpi_x2(t)});
  for (uint16_t f : am::kTurningFeeds) v.push_back({std::to_string(f) + " um/rev feed", am::pitch_um(f)});
  return v;
}

TEST(LatheRatio, EveryTableEntryExactAndReducedOnFourMachines) {
  const am::Machine machines[] = {kSeed, kStepper2mm, kStepper12Tpi, kStepperBelt};
  const std::vector<Entry> entries = every_table_entry();
  ASSERT_EQ(entries.size(), am::kIsoCoarseCount + am::kIsoFineCount + am::kUncCount + am::kUnfCount +
                                am::kCommonTpiCount + am::kTurningFeedsCount);
  for (const am::Machine& m : machines)
    for (const Entry& e : entries)
      for (uint8_t starts = 1; starts <= 4; ++starts)
        for (am::Hand hand : {am::Hand::right, am::Hand::left}) {
          const am::ThreadRequest req = {e.pitch, starts, hand};
          const am::GearRatio g = am::gear_ratio(m, req);
          const Raw r = raw_lambda(m, req);
          const u128 c = gcd(r.num, r.den);
          SCOPED_TRACE(e.name + " starts " + std::to_string(starts));
          ASSERT_EQ(g.status, am::RatioStatus::exact);
          ASSERT_EQ(to_native(g.exact_num), r.num / c);
          ASSERT_EQ(to_native(g.exact_den), r.den / c);
          ASSERT_EQ(g.ratio.num, uint32_t(r.num / c));
          ASSERT_EQ(g.ratio.den, uint32_t(r.den / c));
          ASSERT_EQ(g.error_pm, 0);
          ASSERT_EQ(g.reversed, (hand == am::Hand::left) != m.leadscrew_reversed);
        }
}

// The seed's hardware: lambda = 39 p / 635 for p in 0.01 mm.
TEST(LatheRatio, SeedHardwareRatios) {
  struct Case {
    am::Pitch pitch;
    uint32_t num, den;
  };
  const Case cases[] = {
      {am::pitch_um(1000), 780, 127}, {am::pitch_um(2500), 1950, 127}, {am::pitch_um(40), 156, 635},
      {am::pitch_um(80), 312, 635},   {am::pitch_tpi(20), 39, 5},      {am::pitch_tpi(4), 39, 1},
      {am::pitch_um(1270), 39, 5},    {am::pitch_um(6350), 39, 1},
      // 13 TPI could not be entered on the seed (not a multiple of 0.01 mm);
      // on an 8 TPI leadscrew with 780/40 counts it is exactly 12.
      {am::pitch_tpi(13), 12, 1},     {am::pitch_tpi_x2(23), 312, 23},  // 11.5 TPI
  };
  for (const Case& c : cases) {
    const am::GearRatio g = am::gear_ratio(kSeed, {c.pitch, 1, am::Hand::right});
    EXPECT_EQ(g.status, am::RatioStatus::exact);
    EXPECT_EQ(g.ratio.num, c.num) << c.pitch.num << "/" << c.pitch.den;
    EXPECT_EQ(g.ratio.den, c.den) << c.pitch.num << "/" << c.pitch.den;
  }
  // Pitches in steps of 0.05 mm are k / 127 exactly.
  for (uint32_t um = 50; um <= 10000; um += 50) {
    const am::GearRatio g = am::gear_ratio(kSeed, {am::pitch_um(um), 1, am::Hand::right});
    EXPECT_EQ(127 % g.ratio.den, 0u) << um;
  }
}

// The seed's selection as the digest describes its intended behaviour: for
// n = 1..150 the residual n a - round(n a / b) b, not divided by n; the
// smallest |residual| wins (the first on ties), an exact fraction stops it.
struct SeedChoice {
  uint64_t num, den;
};
SeedChoice seed_choice(uint64_t a, uint64_t b) {
  i128 best = -1;
  SeedChoice c = {0, 1};
  for (uint64_t n = 1; n <= 150; ++n) {
    const i128 g = (i128(2) * n * a + b) / (2 * b);  // round half up
    const i128 res = i128(n) * a - g * b;
    const i128 mag = res < 0 ? -res : res;
    if (best < 0 || mag < best) best = mag, c = {uint64_t(g), n};
    if (res == 0) break;
  }
  return c;
}

// |gamma/delta - 39 p / 635| x 40 spindle pulses x 3175/780 um per LS pulse.
long double seed_error_um(uint64_t gamma, uint64_t delta, uint32_t p) {
  const i128 e = i128(gamma) * 635 - i128(39) * p * delta;  // over 635 delta
  const long double lam_err = (long double)(e < 0 ? -e : e) / (635.0L * delta);
  return lam_err * 40 * 3175.0L / 780;
}

// The lead error from the definition, in pm, truncated toward zero:
// cut lead = (p/q) x spindle counts x (leadscrew pitch / counts per turn).
int64_t independent_error_pm(const am::Machine& m, const am::ThreadRequest& t, uint32_t p, uint32_t q) {
  const i128 cut_num = i128(p) * m.spindle_counts * m.leadscrew.num * m.leadscrew_counts.den;
  const i128 cut_den = i128(q) * m.leadscrew.den * m.leadscrew_counts.num;
  const i128 lead_num = i128(t.pitch.num) * t.starts, lead_den = t.pitch.den;
  const i128 diff = cut_num * lead_den - lead_num * cut_den;  // over cut_den lead_den
  return int64_t(diff * 1000000 / (cut_den * lead_den));       // C++ truncates toward zero
}

TEST(LatheRatio, SeedDenominator150WorstCaseAndOurs) {
  int seed_approximated = 0, ours_approximated = 0;
  long double seed_worst = 0, ours_worst = 0;
  std::vector<uint32_t> seed_worst_at, ours_worst_at;
  for (uint32_t p = 1; p <= 1000; ++p) {  // 0.01 .. 10.00 mm
    const uint64_t a = 39 * p / gcd(39 * p, 635), b = 635 / gcd(39 * p, 635);
    const am::ThreadRequest req = {am::pitch_um(10 * p), 1, am::Hand::right};

    // avrmotion with the full follower width: always exact.
    const am::GearRatio exact = am::gear_ratio(kSeed, req);
    ASSERT_EQ(exact.status, am::RatioStatus::exact);
    ASSERT_EQ(exact.ratio.num, a);
    ASSERT_EQ(exact.ratio.den, b);
    ASSERT_EQ(exact.error_pm, 0);

    if (b > 150) ++seed_approximated;
    const SeedChoice s = seed_choice(a, b);
    const long double se = seed_error_um(s.num, s.den, p);
    if (se > seed_worst + 1e-12L) seed_worst = se, seed_worst_at.clear();
    if (se > seed_worst - 1e-12L) seed_worst_at.push_back(p);

    // avrmotion limited to denominators <= 150, as the seed was.
    const am::GearRatio g = am::gear_ratio(kSeed, req, 150);
    ASSERT_LE(g.ratio.den, 150u);
    ASSERT_EQ(g.status, b > 150 ? am::RatioStatus::approximated : am::RatioStatus::exact);
    if (g.status == am::RatioStatus::approximated) ++ours_approximated;
    ASSERT_EQ(g.error_pm, independent_error_pm(kSeed, req, g.ratio.num, g.ratio.den)) << p;
    const long double oe = seed_error_um(g.ratio.num, g.ratio.den, p);
    ASSERT_NEAR(oe * 1e6L, std::abs((long double)g.error_pm), 1.0L) << p;
    ASSERT_LE(oe, se + 1e-12L) << p;  // never worse than the seed's pick
    if (oe > ours_worst + 1e-12L) ours_worst = oe, ours_worst_at.clear();
    if (oe > ours_worst - 1e-12L) ours_worst_at.push_back(p);
  }
  // The digest: 794 of 1000 need approximation, worst 1.03 um per turn at
  // 1.79 mm (chosen 11/1). 4.56 mm (28/1) and 8.14 mm (50/1) tie with it.
  EXPECT_EQ(seed_approximated, 794);
  EXPECT_EQ(ours_approximated, 794);
  EXPECT_NEAR(seed_worst, 1.0256L, 0.0001L);
  EXPECT_EQ(seed_worst_at, (std::vector<uint32_t>{179, 456, 814}));
  EXPECT_EQ(seed_choice(6981, 635).num, 11u);
  EXPECT_EQ(seed_choice(6981, 635).den, 1u);
  // The nearest fraction (normalised by n) halves the worst case: 0.513 um
  // per turn, at 2.28, 4.07 and 8.63 mm (integers again: 14, 25, 53).
  EXPECT_NEAR(ours_worst, 0.5128L, 0.0001L);
  EXPECT_EQ(ours_worst_at, (std::vector<uint32_t>{228, 407, 863}));
  // Two of the seed's own table rows under the same bound.
  EXPECT_EQ(seed_choice(156, 635).num, 14u);
  EXPECT_EQ(seed_choice(156, 635).den, 57u);
  EXPECT_EQ(seed_choice(312, 635).num, 57u);
  EXPECT_EQ(seed_choice(312, 635).den, 116u);
  const am::GearRatio fine = am::gear_ratio(kSeed, {am::pitch_um(40), 1, am::Hand::right}, 150);
  const am::GearRatio coarse = am::gear_ratio(kSeed, {am::pitch_um(80), 1, am::Hand::right}, 150);
  EXPECT_EQ(fine.ratio.num, 14u);
  EXPECT_EQ(fine.ratio.den, 57u);
  EXPECT_EQ(coarse.ratio.num, 57u);
  EXPECT_EQ(coarse.ratio.den, 116u);
  // 1.79 mm at denominator 150: ours is the semiconvergent 1649/150.
  const am::GearRatio p179 = am::gear_ratio(kSeed, {am::pitch_um(1790), 1, am::Hand::right}, 150);
  EXPECT_EQ(p179.ratio.num, 1649u);
  EXPECT_EQ(p179.ratio.den, 150u);
  EXPECT_EQ(p179.error_pm, independent_error_pm(kSeed, {am::pitch_um(1790), 1, am::Hand::right}, 1649, 150));
  EXPECT_NEAR(p179.error_pm * 1e-6, -0.0598, 0.0001);  // 1649/150 < 6981/635: the thread is short
}

TEST(LatheRatio, ErrorReportMatchesDefinitionOnRandomMachines) {
  std::mt19937 rng(21);
  int approximated = 0;
  for (int i = 0; i < 20000; ++i) {
    auto pick = [&rng](uint32_t n) { return uint32_t(1 + rng() % n); };
    const am::Machine m = {{pick(20000), pick(64)}, {pick(60000), pick(60)}, uint16_t(pick(5000)),
                           bool(rng() & 1)};
    const am::ThreadRequest t = {{pick(20000), pick(160)}, uint8_t(pick(6)),
                                 (rng() & 1) ? am::Hand::left : am::Hand::right};
    const uint32_t max_den = pick(2000);
    const am::GearRatio g = am::gear_ratio(m, t, max_den);
    const Raw r = raw_lambda(m, t);
    if (r.num / r.den >= (u128(1) << 32)) {
      ASSERT_EQ(g.status, am::RatioStatus::out_of_range);
      continue;
    }
    if (g.status == am::RatioStatus::out_of_range) {
      // Only when lambda is so small that the nearest fraction is 0.
      ASSERT_LE(r.num * 2 * max_den, r.den) << i;
      continue;
    }
    const u128 c = gcd(r.num, r.den);
    ASSERT_EQ(to_native(g.exact_num), r.num / c);
    ASSERT_EQ(to_native(g.exact_den), r.den / c);
    ASSERT_LE(g.ratio.den, max_den);
    if (g.status == am::RatioStatus::exact) {
      ASSERT_EQ(u128(g.ratio.num) * r.den, u128(g.ratio.den) * r.num);
      ASSERT_EQ(g.error_pm, 0);
    } else {
      ++approximated;
      ASSERT_NE(u128(g.ratio.num) * r.den, u128(g.ratio.den) * r.num);
      const int64_t ref = independent_error_pm(m, t, g.ratio.num, g.ratio.den);
      const int64_t sat = ref > INT32_MAX ? INT32_MAX : (ref < -INT32_MAX ? -INT32_MAX : ref);
      ASSERT_EQ(g.error_pm, sat) << i;
    }
  }
  EXPECT_GT(approximated, 5000);
}

// gear_ratio_exact() is gear_ratio() where that is exact and refuses
// (out_of_range) wherever gear_ratio() approximates or refuses.
TEST(LatheRatio, ExactOnlyVariantRefusesWhatWouldBeApproximated) {
  std::mt19937 rng(22);
  int exact = 0, refused_approximation = 0;
  for (int i = 0; i < 20000; ++i) {
    auto pick = [&rng](uint32_t n) { return uint32_t(1 + rng() % n); };
    const am::Machine m = {{pick(20000), pick(64)}, {pick(60000), pick(60)}, uint16_t(pick(5000)),
                           bool(rng() & 1)};
    const am::ThreadRequest t = {{pick(200000), pick(1000)}, uint8_t(pick(8)),
                                 (rng() & 1) ? am::Hand::left : am::Hand::right};
    const am::GearRatio full = am::gear_ratio(m, t);
    const am::GearRatio only = am::gear_ratio_exact(m, t);
    const Raw r = raw_lambda(m, t);
    if (full.status == am::RatioStatus::exact) {
      ++exact;
      ASSERT_EQ(only.status, am::RatioStatus::exact) << i;
      ASSERT_EQ(u128(only.ratio.num) * r.den, u128(only.ratio.den) * r.num) << i;
      ASSERT_EQ(only.reversed, full.reversed);
    } else {
      if (full.status == am::RatioStatus::approximated) ++refused_approximation;
      ASSERT_EQ(only.status, am::RatioStatus::out_of_range) << i;
    }
  }
  EXPECT_GT(exact, 1000);
  EXPECT_GT(refused_approximation, 1000);
}

TEST(LatheRatio, FallsBackOnlyWhenTheFollowerCannotHoldIt) {
  // lambda = 1 / (10^9 + 7): exact for one start (denominator below 2^31) ...
  const am::Machine m = {am::pitch_um(1), {1, 1}, 1, false};
  const am::ThreadRequest one = {{1, 1000000007}, 1, am::Hand::right};
  const am::GearRatio g1 = am::gear_ratio(m, one);
  EXPECT_EQ(g1.status, am::RatioStatus::exact);
  EXPECT_EQ(g1.ratio.den, 1000000007u);
  // ... but three starts on a 1-count spindle need the phase unit 1/3, so the
  // denominator must stay below 2^31 / 3.
  const am::ThreadRequest three = {{1, 1000000007}, 3, am::Hand::right};
  const am::GearRatio g3 = am::gear_ratio(m, three);
  EXPECT_EQ(g3.status, am::RatioStatus::approximated);
  EXPECT_LE(g3.ratio.den, am::kMaxDen / 3);
  // 3/1000000007 = [0; 333333335, 1, 2]: the convergent 1/333333336 and the
  // semiconvergent 2/666666671 (j = 1, half of the next term) both have
  // |p D - q N| = 1, so the larger denominator is the nearer one.
  EXPECT_EQ(g3.ratio.num, 2u);
  EXPECT_EQ(g3.ratio.den, 666666671u);
  EXPECT_EQ(g3.error_pm, independent_error_pm(m, three, g3.ratio.num, g3.ratio.den));
  am::Follower f;
  EXPECT_TRUE(f.reset(g3.ratio, g3.reversed, am::start_phase(1, 3, m.spindle_counts)));

  // A reduced denominator above 2^31 (primes 2^32 - 5 and 65521, numerator
  // with 2^32 - 17): approximated, and the error is far below a picometre
  // per turn.
  const am::Machine big = {{4294967291u, 1}, {4294967279u, 1}, 65521, false};
  const am::ThreadRequest t = {am::pitch_um(1000), 1, am::Hand::right};
  const am::GearRatio gb = am::gear_ratio(big, t);
  EXPECT_EQ(gb.status, am::RatioStatus::approximated);
  EXPECT_EQ(to_native(gb.exact_den), u128(4294967291u) * 65521);
  EXPECT_EQ(gb.error_pm, independent_error_pm(big, t, gb.ratio.num, gb.ratio.den));
  EXPECT_EQ(gb.error_pm, 0);
  EXPECT_NE(u128(gb.ratio.num) * 4294967291u * 65521, u128(gb.ratio.den) * 1000 * 4294967279u);
}

TEST(LatheRatio, OutOfRange) {
  constexpr am::RatioStatus oor = am::RatioStatus::out_of_range;
  const am::Hand rh = am::Hand::right;
  const am::ThreadRequest t = {am::pitch_um(1000), 1, rh};
  EXPECT_EQ(am::gear_ratio(kSeed, {am::pitch_um(0), 1, rh}).status, oor);
  EXPECT_EQ(am::gear_ratio(kSeed, {am::pitch_um(1000), 0, rh}).status, oor);
  EXPECT_EQ(am::gear_ratio({am::pitch_um(3175), {780, 1}, 0, false}, t).status, oor);
  EXPECT_EQ(am::gear_ratio(kSeed, t, 0).status, oor);
  // lambda >= 2^32 leadscrew counts per spindle count.
  const am::Machine coarse = {am::pitch_um(1), {0xFFFFFFFFu, 1}, 1, false};
  EXPECT_EQ(am::gear_ratio(coarse, {am::pitch_um(2), 1, rh}).status, oor);
  EXPECT_EQ(am::gear_ratio(coarse, {am::pitch_um(1), 1, rh}).status, am::RatioStatus::exact);
  // A reduced denominator above 64 bits.
  const am::Machine wide = {{4294967291u, 1}, {1, 4294967279u}, 65521, false};
  EXPECT_EQ(am::gear_ratio(wide, {{1, 4294967231u}, 1, rh}).status, oor);
  // So small that the nearest fraction with a denominator <= 10 is 0.
  EXPECT_EQ(am::gear_ratio(kSeed, {am::pitch_um(1), 1, rh}, 10).status, oor);
}

}  // namespace
