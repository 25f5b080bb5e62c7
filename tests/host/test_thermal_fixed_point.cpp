// core/thermal/fixed_point.h: mul_div_round against 128-bit arithmetic.
#include <gtest/gtest.h>

#include <random>

#include "core/thermal/fixed_point.h"

namespace {

uint64_t reference(uint32_t a, uint32_t b, uint32_t c) {
  const unsigned __int128 p = static_cast<unsigned __int128>(a) * b;
  return uint64_t((2 * p + c) / (2 * static_cast<unsigned __int128>(c)));  // halves up
}

TEST(ThermalFixedPoint, MulDivRoundMatches128BitArithmetic) {
  std::mt19937 rng(3);
  int checked = 0;
  for (int n = 0; n < 200000; ++n) {
    const int kind = n % 4;
    uint32_t a = rng(), b = rng(), c = rng() >> (rng() % 31);
    if (kind == 1) a >>= rng() % 32;
    if (kind == 2) b >>= rng() % 32;
    if (kind == 3) c = uint32_t(1) << (rng() % 32);
    c = c == 0 ? 1 : c > (uint32_t(1) << 31) ? uint32_t(1) << 31 : c;
    const uint64_t want = reference(a, b, c);
    if (want > 0xFFFFFFFFull) continue;  // outside the contract
    ASSERT_EQ(am::mul_div_round(a, b, c), want) << a << " * " << b << " / " << c;
    ++checked;
  }
  EXPECT_GT(checked, 50000);
}

TEST(ThermalFixedPoint, MulDivRoundEdges) {
  EXPECT_EQ(am::mul_div_round(0, 12345, 7), 0u);
  EXPECT_EQ(am::mul_div_round(12345, 0, 7), 0u);
  EXPECT_EQ(am::mul_div_round(0xFFFFFFFFu, 1, 1), 0xFFFFFFFFu);
  EXPECT_EQ(am::mul_div_round(0xFFFFFFFFu, 0x80000000u, 0x80000000u), 0xFFFFFFFFu);
  EXPECT_EQ(am::mul_div_round(1, 1, 2), 1u);  // a half rounds up
  EXPECT_EQ(am::mul_div_round(1, 1, 3), 0u);
  EXPECT_EQ(am::mul_div_round(2, 1, 3), 1u);
  EXPECT_EQ(am::mul_div_round(5, 1, 2), 3u);
  static_assert(am::mul_div_round(22200, 65536, 100000) == 14549, "constexpr");
  EXPECT_EQ(am::clamp32(-5, -3, 3), -3);
  EXPECT_EQ(am::clamp32(5, -3, 3), 3);
  EXPECT_EQ(am::clamp32(2, -3, 3), 2);
}

}  // namespace
