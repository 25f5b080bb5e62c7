// The look-ahead planner's integer helpers (core/motion/lookahead_math.h)
// against exact references computed here with 128-bit integers and long
// double: square roots (exact and approximate), the 24-bit norm and its
// reciprocal, the 32-bit fast paths of division and shifts, and Fp16, the
// 16-bit mantissa number of the junction formula.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "core/motion/lookahead_math.h"

using namespace am::lookahead_detail;

namespace {

std::vector<uint64_t> samples() {
  std::vector<uint64_t> v = {0, 1, 2, 3, 4, 15, 16, 17, 0xFFFFFFFFull, 0x100000000ull, 0x100000001ull,
                             0xFFFFFFFFFFFFFFFFull, 0xFFFFFFFE00000001ull, 0xFFFFFFFE00000000ull};
  std::mt19937_64 rng(5);
  for (int i = 0; i < 20000; ++i) {
    const int bits = int(rng() % 64) + 1;
    v.push_back(rng() >> (64 - bits));
    const uint64_t k = rng() >> (64 - (bits + 1) / 2);  // squares and neighbours
    v.push_back(k * k);
    if (k) v.push_back(k * k - 1);
    if (k * k != ~0ull) v.push_back(k * k + 1);
  }
  return v;
}

double fp_value(Fp16 a) { return std::ldexp(double(a.m), a.e); }

}  // namespace

TEST(LookaheadMath, ExactSquareRootIsTheFloor) {
  for (uint64_t x : samples()) {
    const unsigned __int128 r = isqrt_exact(x);
    EXPECT_LE(r * r, x) << x;
    EXPECT_GT((r + 1) * (r + 1), x) << x;
  }
}

TEST(LookaheadMath, ApproximateSquareRootIsNeverAboveAndWithin2e15) {
  for (uint64_t x : samples()) {
    const uint32_t r = isqrt_approx(x);
    const uint32_t exact = isqrt_exact(x);
    EXPECT_LE(r, exact) << x;
    if (x < (uint64_t(1) << 32)) {
      EXPECT_EQ(r, exact) << x;
    } else {
      EXPECT_GE(double(r), double(exact) * (1 - std::ldexp(1.0, -15)) - 1) << x;
    }
  }
}

TEST(LookaheadMath, Norm24AndItsReciprocal) {
  std::mt19937 rng(9);
  std::vector<uint32_t> xs = {0x40000000u, 0x40000001u, 0xFFFFFFFFu, 0xFFFE0001u, 0x7FFFFFFFu};
  for (int i = 0; i < 200000; ++i) xs.push_back(0x40000000u + uint32_t(rng() % 0xC0000000u));
  double worst_n = 0, worst_r = 0;
  for (uint32_t x : xs) {
    uint32_t n, r;
    norm24(x, n, r);
    const long double root = std::sqrt((long double)x) * 256;
    EXPECT_GE(n, 1u << 23);
    EXPECT_LT(n, 1u << 24);
    worst_n = std::max(worst_n, double(std::fabs(n - root)));
    const long double want = std::ldexp(1.0L, 48) / n;
    worst_r = std::max(worst_r, double(std::fabs(r - want) / want));
  }
  EXPECT_LE(worst_n, 1.01);  // n within about one unit (2^-23) of sqrt(x) 2^8
  EXPECT_LE(worst_r, std::ldexp(1.0, -23));  // r within 2^-23 of 2^48 / n
}

TEST(LookaheadMath, DivisionAndShiftsMatchThePlainOperators) {
  std::mt19937_64 rng(3);
  for (int i = 0; i < 100000; ++i) {
    const uint64_t n = rng() >> (rng() % 64), d = (rng() >> (rng() % 64)) | 1;
    EXPECT_EQ(div_u64(n, d), n / d);
    const uint8_t s = uint8_t(rng() % 64);
    const uint64_t x = rng() >> (rng() % 64);
    if ((x >> s) <= 0xFFFFFFFFull) {
      EXPECT_EQ(shr_to32(x, s), uint32_t(x >> s));
    }
    const uint32_t y = uint32_t(rng());
    const uint8_t t = uint8_t(rng() % 32);
    EXPECT_EQ(shr32(y, t), y >> t);
    EXPECT_EQ(shl32(y, t), uint32_t(y << t));
    EXPECT_EQ(bit_length(x), x ? 64 - __builtin_clzll(x) : 0);
    EXPECT_EQ(hi32(x), uint32_t(x >> 32));
    EXPECT_EQ(make64(uint32_t(x), hi32(x)), x);
  }
}

TEST(LookaheadMath, Fp16OperationsTruncateTo16Bits) {
  std::mt19937_64 rng(4);
  const double ulp = std::ldexp(1.0, -15);
  for (int i = 0; i < 100000; ++i) {
    const uint32_t a = uint32_t(rng() >> (32 + rng() % 32)) | 1, b = uint32_t(rng() >> (32 + rng() % 32)) | 1;
    const int16_t ea = int16_t(int(rng() % 61) - 30), eb = int16_t(int(rng() % 61) - 30);
    const Fp16 fa = fp_make(a, ea), fb = fp_make(b, eb);
    ASSERT_GE(fa.m, 0x8000u);
    const double va = std::ldexp(double(a), ea);
    EXPECT_LE(fp_value(fa), va);
    EXPECT_GE(fp_value(fa), va * (1 - ulp));
    const double p = fp_value(fa) * fp_value(fb), q = fp_value(fa) / fp_value(fb), s = fp_value(fa) + fp_value(fb);
    EXPECT_LE(fp_value(fp_mul(fa, fb)), p);
    EXPECT_GE(fp_value(fp_mul(fa, fb)), p * (1 - ulp));
    EXPECT_LE(fp_value(fp_div(fa, fb)), q);
    EXPECT_GE(fp_value(fp_div(fa, fb)), q * (1 - ulp));
    EXPECT_LE(fp_value(fp_add(fa, fb)), s);
    EXPECT_GE(fp_value(fp_add(fa, fb)), s * (1 - 2 * ulp));
    EXPECT_EQ(fp_less(fa, fb), fp_value(fa) < fp_value(fb));
    const uint64_t x = rng() >> (rng() % 64);
    const Fp16 fx = fp_make64(x, 0);
    if (x) {
      EXPECT_LE(fp_value(fx), double(x));
      EXPECT_GE(fp_value(fx), double(x) * (1 - ulp));
    }
  }
  // fp_to_u64: the floor, capped; zero is zero.
  EXPECT_EQ(fp_to_u64(Fp16{0, 0}, 100), 0u);
  EXPECT_EQ(fp_to_u64(Fp16{0x8000u, -15}, 100), 1u);
  EXPECT_EQ(fp_to_u64(Fp16{0xC000u, -15}, 100), 1u);
  EXPECT_EQ(fp_to_u64(Fp16{0x8000u, -16}, 100), 0u);
  EXPECT_EQ(fp_to_u64(Fp16{0x8000u, 10}, ~0ull), uint64_t(0x8000u) << 10);
  EXPECT_EQ(fp_to_u64(Fp16{0x8000u, 60}, uint64_t(1) << 58), uint64_t(1) << 58);
  EXPECT_EQ(fp_to_u64(Fp16{0xFFFFu, 40}, uint64_t(1) << 58), uint64_t(0xFFFFu) << 40);
  EXPECT_EQ(fp_to_u64(Fp16{0xFFFFu, 43}, uint64_t(1) << 58), uint64_t(1) << 58);
}
