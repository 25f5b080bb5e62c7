// core/lathe/wide.h and rational.h against independent references: the
// compiler's unsigned __int128 for the limb arithmetic, and a brute-force
// search over every denominator for the continued-fraction approximation.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>

#include "core/lathe/rational.h"
#include "core/lathe/wide.h"

namespace {

using u128 = unsigned __int128;

u128 to_native(const am::U128& x) {
  u128 v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 32) | x.w[i];
  return v;
}

am::U128 from_native(u128 v) {
  am::U128 x;
  for (int i = 0; i < 4; ++i, v >>= 32) x.w[i] = uint32_t(v);
  return x;
}

u128 random_wide(std::mt19937_64& rng) {
  // Mix magnitudes: full 128-bit, 64-bit, 32-bit and tiny values.
  const u128 v = (u128(rng()) << 64) | rng();
  switch (rng() % 4) {
    case 0: return v;
    case 1: return v >> 64;
    case 2: return v >> 96;
    default: return v >> (64 + 32 + 24);
  }
}

TEST(LatheWide, MulSmallSubCmpMatchNative128) {
  std::mt19937_64 rng(11);
  for (int i = 0; i < 200000; ++i) {
    const u128 a = random_wide(rng), b = random_wide(rng);
    const uint32_t m = uint32_t(rng() >> (rng() % 32));
    am::U128 x = from_native(a);
    const uint32_t carry = am::mul_small(x, m);
    // Reference: the full 160-bit product split into the low 128 bits and
    // the overflow above them.
    const u128 lo = a * m;
    const u128 hi = (((a >> 64) * m) + ((((a << 64) >> 64) * m) >> 64)) >> 64;
    ASSERT_EQ(to_native(x), lo);
    ASSERT_EQ(carry, uint32_t(hi));

    am::U128 y = from_native(a);
    const bool borrow = am::sub(y, from_native(b));
    ASSERT_EQ(to_native(y), u128(a - b));
    ASSERT_EQ(borrow, a < b);
    ASSERT_EQ(am::cmp(from_native(a), from_native(b)), a < b ? -1 : (a > b ? 1 : 0));
  }
}

TEST(LatheWide, DivmodMatchesNative128) {
  std::mt19937_64 rng(12);
  for (int i = 0; i < 100000; ++i) {
    const u128 n = random_wide(rng);
    u128 d = random_wide(rng);
    if (d == 0) d = 1;
    am::U128 q, r;
    am::divmod(from_native(n), from_native(d), q, r);
    ASSERT_EQ(to_native(q), n / d);
    ASSERT_EQ(to_native(r), n % d);
  }
  // Divisors above 2^127 exercise the bit shifted out of the remainder.
  const u128 top = ~u128(0);
  am::U128 q, r;
  am::divmod(from_native(top), from_native(top - 5), q, r);
  EXPECT_EQ(to_native(q), u128(1));
  EXPECT_EQ(to_native(r), u128(5));
  // The quotient may be written over the dividend.
  am::U128 n = from_native(u128(1000003) * 999983 + 17);
  am::divmod(n, am::u128(999983), n, r);
  EXPECT_EQ(to_native(n), u128(1000003));
  EXPECT_EQ(to_native(r), u128(17));
}

TEST(LatheRational, Gcd) {
  EXPECT_EQ(am::gcd32(0, 7), 7u);
  EXPECT_EQ(am::gcd32(7, 0), 7u);
  EXPECT_EQ(am::gcd32(3175 * 40, 780 * 100), 1000u);  // 127000 and 78000
  EXPECT_EQ(am::gcd32(0xFFFFFFFFu, 0xFFFFFFFEu), 1u);
}

// |p/q - N/D| = |p D - q N| / (q D); for one N/D the common factor 1/D drops
// out of every comparison, so a distance is kept as e / q.
struct Distance {
  u128 e, q;
};
Distance distance(u128 p, u128 q, u128 N, u128 D) {
  const u128 a = p * D, b = q * N;
  return {a > b ? a - b : b - a, q};
}
int compare(const Distance& x, const Distance& y) {
  // e < 2^97 and q <= 500 in the wide test, tiny elsewhere: no overflow.
  const u128 l = x.e * y.q, r = y.e * x.q;
  return l < r ? -1 : (l > r ? 1 : 0);
}

// Nearest p/q with p <= P, 1 <= q <= Q by trying every denominator.
struct Best {
  uint32_t p, q;
};
Best brute_force(uint64_t N, uint64_t D, uint32_t P, uint32_t Q) {
  Best best = {0, 0};
  Distance bd = {1, 0};  // infinitely far (q = 0 marks "none yet")
  for (uint32_t q = 1; q <= Q; ++q) {
    const u128 fl = u128(q) * N / D;
    for (u128 p : {fl, fl + 1}) {
      if (p > P) p = P;
      const Distance d = distance(p, q, N, D);
      if (bd.q == 0 || compare(d, bd) < 0) best = {uint32_t(p), q}, bd = d;
    }
  }
  return best;
}

void check_against_brute_force(uint64_t N, uint64_t D, uint32_t P, uint32_t Q) {
  const am::Approximation a = am::best_rational(am::u128_64(N), am::u128_64(D), P, Q);
  ASSERT_GE(a.den, 1u);
  ASSERT_LE(a.den, Q);
  ASSERT_LE(a.num, P);
  const Best b = brute_force(N, D, P, Q);
  const Distance da = distance(a.num, a.den, N, D), db = distance(b.p, b.q, N, D);
  ASSERT_EQ(compare(da, db), 0) << N << "/" << D << " P=" << P << " Q=" << Q << ": got " << a.num
                                << "/" << a.den << ", brute force " << b.p << "/" << b.q;
  // Ties go to the smaller denominator; the brute force keeps the first.
  ASSERT_EQ(a.den, b.q) << N << "/" << D << " P=" << P << " Q=" << Q;
  // The reported e = p D - q N, magnitude and sign.
  const u128 pd = u128(a.num) * D, qn = u128(a.den) * N;
  ASSERT_EQ(to_native(a.error), pd > qn ? pd - qn : qn - pd);
  if (pd != qn) {
    ASSERT_EQ(a.error_positive, pd > qn);
  }
}

TEST(LatheRational, BestRationalMatchesBruteForceForSmallBounds) {
  std::mt19937_64 rng(13);
  for (int i = 0; i < 4000; ++i) {
    const uint64_t D = 1 + rng() % 100000;
    const uint64_t N = rng() % (4 * D + 1);  // lambda from 0 to 4
    for (uint32_t Q : {1u, 2u, 3u, 7u, 20u, 61u}) {
      check_against_brute_force(N, D, 0xFFFFFFFFu, Q);
      check_against_brute_force(N, D, Q, 200);               // the numerator bound binds
      check_against_brute_force(N, D, Q + 3, Q);             // both
    }
  }
  // Every fraction with small terms, every bound up to 40.
  for (uint64_t D = 1; D <= 40; ++D)
    for (uint64_t N = 0; N <= 90; ++N)
      for (uint32_t Q = 1; Q <= 40; Q += 3) check_against_brute_force(N, D, 0xFFFFFFFFu, Q);
}

TEST(LatheRational, BestRationalOnWideInputs) {
  // 64-bit N and D (the remainders then need all of the wide arithmetic),
  // with the bound kept small enough to try every denominator.
  std::mt19937_64 rng(14);
  for (int i = 0; i < 300; ++i) {
    const uint64_t D = rng() | (uint64_t(1) << 63), N = rng() >> (rng() % 8);
    check_against_brute_force(N, D, 0xFFFFFFFFu, 500);
  }
}

TEST(LatheRational, ExactWhenItFits) {
  const am::Approximation a = am::best_rational(am::u128(780 * 6), am::u128(127 * 6), 1000, 127);
  EXPECT_EQ(a.num, 780u);
  EXPECT_EQ(a.den, 127u);
  EXPECT_TRUE(am::is_zero(a.error));
  const am::Approximation z = am::best_rational(am::u128(0), am::u128(9), 10, 10);
  EXPECT_EQ(z.num, 0u);
  EXPECT_EQ(z.den, 1u);
}

// The thesis's example 131/80 = [1; 1, 1, 1, 3, 7]. With denominators up to
// 11 the best fraction is the convergent 18/11 (error 1/880 = 0.001136); up
// to 50 it is the semiconvergent 77/47 (3/3760 = 0.000798), where the seed's
// truncation at denominator 50 gave 81/50 (0.0175, 22 times worse).
TEST(LatheRational, ThesisExample131Over80) {
  const am::Approximation a11 = am::best_rational(am::u128(131), am::u128(80), 1000, 11);
  EXPECT_EQ(a11.num, 18u);
  EXPECT_EQ(a11.den, 11u);
  EXPECT_EQ(to_native(a11.error), u128(1));  // |18 80 - 11 131| = 1
  EXPECT_NEAR(131.0 / 80 - 18.0 / 11, 0.001136, 0.0000005);
  const am::Approximation a50 = am::best_rational(am::u128(131), am::u128(80), 1000, 50);
  EXPECT_EQ(a50.num, 77u);
  EXPECT_EQ(a50.den, 47u);
  EXPECT_TRUE(a50.error_positive);  // 77/47 = 1.638298 > 1.6375
  EXPECT_NEAR(77.0 / 47 - 131.0 / 80, 3.0 / 3760, 1e-12);
  EXPECT_LT(3.0 / 3760 * 20, 0.0175);
}

}  // namespace
