// core/text/fixed_number.h against references computed differently: decimal
// strings scaled with 128-bit integers, conversions with 128-bit exact
// rational arithmetic, formatting with snprintf.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>
#include <string>

#include "core/text/fixed_number.h"

using am::NumberStatus;

namespace {

// Reference: value * 10^digits of a decimal string, rounded half away from
// zero, from the whole digit string as one 128-bit integer.
struct Ref {
  bool ok;
  bool in_range;
  __int128 value;
};

Ref reference_fixed(const std::string& s, unsigned digits) {
  size_t i = 0;
  bool negative = false;
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) negative = s[i++] == '-';
  __int128 mantissa = 0;
  int frac = -1;  // digits after the point, -1 before it
  bool any = false;
  bool huge = false;
  for (; i < s.size(); ++i) {
    const char c = s[i];
    if (c >= '0' && c <= '9') {
      any = true;
      if (mantissa > (__int128(1) << 100)) huge = true;
      else mantissa = mantissa * 10 + (c - '0');
      if (frac >= 0) ++frac;
    } else if (c == '.' && frac < 0) {
      frac = 0;
    } else {
      break;
    }
  }
  if (!any) return {false, false, 0};
  if (frac < 0) frac = 0;
  __int128 v;
  if (unsigned(frac) <= digits) {
    v = mantissa;
    for (unsigned k = frac; k < digits; ++k) v *= 10;
  } else {
    __int128 div = 1;
    for (unsigned k = digits; k < unsigned(frac); ++k) div *= 10;
    v = (mantissa * 2 + div) / (div * 2);  // half away from zero on the magnitude
  }
  const bool in_range = !huge && v <= am::kFixedMax;
  return {true, in_range, negative ? -v : v};
}

NumberStatus parse(const char* s, unsigned digits, int32_t& out, const char** end = nullptr) {
  const char* p = s;
  const NumberStatus st = am::parse_fixed(p, uint8_t(digits), out);
  if (end) *end = p;
  return st;
}

}  // namespace

TEST(FixedNumber, RoundsHalfAwayFromZeroOnTheFirstDroppedDigit) {
  int32_t v = 0;
  ASSERT_EQ(parse("0.00005", 4, v), NumberStatus::ok);
  EXPECT_EQ(v, 1);
  ASSERT_EQ(parse("-0.00005", 4, v), NumberStatus::ok);
  EXPECT_EQ(v, -1);
  ASSERT_EQ(parse("0.000049999", 4, v), NumberStatus::ok);
  EXPECT_EQ(v, 0);
  // 1 um resolution (3 digits): X0.0005 rounds up, X0.00049 down, never truncated.
  ASSERT_EQ(parse("0.0005", 3, v), NumberStatus::ok);
  EXPECT_EQ(v, 1);
  ASSERT_EQ(parse("0.00049", 3, v), NumberStatus::ok);
  EXPECT_EQ(v, 0);
  ASSERT_EQ(parse("-1.23456", 4, v), NumberStatus::ok);
  EXPECT_EQ(v, -12346);
  ASSERT_EQ(parse("2.99999", 4, v), NumberStatus::ok);
  EXPECT_EQ(v, 30000);
  ASSERT_EQ(parse("1.5", 0, v), NumberStatus::ok);
  EXPECT_EQ(v, 2);
  ASSERT_EQ(parse("-2.5", 0, v), NumberStatus::ok);
  EXPECT_EQ(v, -3);
}

TEST(FixedNumber, FormsAndWhereTheNumberEnds) {
  int32_t v = 0;
  const char* end = nullptr;
  ASSERT_EQ(parse("1.", 4, v, &end), NumberStatus::ok);
  EXPECT_EQ(v, 10000);
  ASSERT_EQ(parse(".5", 4, v), NumberStatus::ok);
  EXPECT_EQ(v, 5000);
  ASSERT_EQ(parse("+.5", 4, v), NumberStatus::ok);
  EXPECT_EQ(v, 5000);
  ASSERT_EQ(parse("-0", 4, v), NumberStatus::ok);
  EXPECT_EQ(v, 0);
  ASSERT_EQ(parse("00000000000000000012.5000000000000000", 4, v), NumberStatus::ok);
  EXPECT_EQ(v, 125000);
  // No exponent: the number ends at the letter.
  const char* s = "1e5";
  ASSERT_EQ(parse(s, 4, v, &end), NumberStatus::ok);
  EXPECT_EQ(v, 10000);
  EXPECT_EQ(end, s + 1);
  s = "12.25X";
  ASSERT_EQ(parse(s, 4, v, &end), NumberStatus::ok);
  EXPECT_EQ(end, s + 5);
  bool point = true;
  const char* p = "42";
  ASSERT_EQ(am::parse_fixed(p, 0, v, point), NumberStatus::ok);
  EXPECT_FALSE(point);
  p = "42.0";
  ASSERT_EQ(am::parse_fixed(p, 0, v, point), NumberStatus::ok);
  EXPECT_TRUE(point);
}

TEST(FixedNumber, MalformedNumbersAreBadAndLeaveThePointer) {
  for (const char* s : {"", "-", "+", ".", "-.", "+.", "x1", " 1", "- 1", "1.2.3", "1..", "..5"}) {
    int32_t v = 77;
    const char* end = nullptr;
    EXPECT_EQ(parse(s, 4, v, &end), NumberStatus::bad) << s;
    EXPECT_EQ(end, s) << s;
    EXPECT_EQ(v, 77) << s;
  }
}

TEST(FixedNumber, RangeIsSymmetricAndNeverWraps) {
  int32_t v = 0;
  ASSERT_EQ(parse("214748.3647", 4, v), NumberStatus::ok);
  EXPECT_EQ(v, 2147483647);
  ASSERT_EQ(parse("-214748.3647", 4, v), NumberStatus::ok);
  EXPECT_EQ(v, -2147483647);
  ASSERT_EQ(parse("214748.36474", 4, v), NumberStatus::ok);  // rounds down
  EXPECT_EQ(v, 2147483647);
  v = 5;
  EXPECT_EQ(parse("214748.36475", 4, v), NumberStatus::out_of_range);  // rounding alone overflows
  EXPECT_EQ(v, 5);
  EXPECT_EQ(parse("214748.3648", 4, v), NumberStatus::out_of_range);
  EXPECT_EQ(parse("-214748.3648", 4, v), NumberStatus::out_of_range);  // -2^31 is refused too
  EXPECT_EQ(parse("429496.7296", 4, v), NumberStatus::out_of_range);   // 2^32: would wrap to 0
  EXPECT_EQ(parse("99999999999999999999999", 4, v), NumberStatus::out_of_range);
  EXPECT_EQ(parse("1000000", 4, v), NumberStatus::out_of_range);
  ASSERT_EQ(parse("2147483647", 0, v), NumberStatus::ok);
  EXPECT_EQ(v, 2147483647);
  EXPECT_EQ(parse("2147483648", 0, v), NumberStatus::out_of_range);
}

TEST(FixedNumber, RandomDecimalStringsMatchTheReference) {
  std::mt19937 rng(8);
  for (int n = 0; n < 20000; ++n) {
    std::string s;
    const int sign = rng() % 3;
    if (sign == 1) s += '-';
    if (sign == 2) s += '+';
    const int int_digits = rng() % 8;
    for (int k = 0; k < int_digits; ++k) s += char('0' + rng() % 10);
    if (rng() % 4 != 0) {
      s += '.';
      const int frac_digits = rng() % 9;
      for (int k = 0; k < frac_digits; ++k) s += char('0' + (rng() % 4 == 0 ? 5 : rng() % 10));
    }
    for (unsigned digits : {0u, 3u, 4u}) {
      const Ref ref = reference_fixed(s, digits);
      int32_t v = 0;
      const NumberStatus st = parse(s.c_str(), digits, v);
      if (!ref.ok) {
        EXPECT_EQ(st, NumberStatus::bad) << s;
      } else if (!ref.in_range) {
        EXPECT_EQ(st, NumberStatus::out_of_range) << s << " at " << digits;
      } else {
        ASSERT_EQ(st, NumberStatus::ok) << s << " at " << digits;
        EXPECT_EQ(__int128(v), ref.value) << s << " at " << digits;
      }
    }
  }
}

TEST(FixedNumber, ConversionsRoundHalfAwayFromZeroExactly) {
  int32_t v = 0;
  // 1 inch = 25.4 mm exactly: G20 X1 at 80 steps/mm is 2032 steps.
  ASSERT_TRUE(am::inch_to_length(10000, v));
  EXPECT_EQ(v, 254000);
  int32_t steps = 0;
  ASSERT_TRUE(am::length_to_steps(v, 80000, steps));
  EXPECT_EQ(steps, 2032);
  ASSERT_TRUE(am::inch_to_length(-1, v));  // -0.0001 in = -2.54 um -> -25
  EXPECT_EQ(v, -25);
  ASSERT_TRUE(am::inch_to_length(3, v));  // 76.2 -> 76
  EXPECT_EQ(v, 76);
  ASSERT_TRUE(am::inch_to_length(-2, v));  // -50.8 -> -51
  EXPECT_EQ(v, -51);
  // Half a step rounds away from zero: 0.00625 mm at 80 steps/mm = 0.5 step.
  ASSERT_TRUE(am::length_to_steps(62, 80000, steps));  // 0.0062 mm = 0.496 step
  EXPECT_EQ(steps, 0);
  ASSERT_TRUE(am::scale_round(625, 80000, 100000000, steps));  // 0.5 exactly
  EXPECT_EQ(steps, 1);
  ASSERT_TRUE(am::scale_round(-625, 80000, 100000000, steps));
  EXPECT_EQ(steps, -1);
  ASSERT_TRUE(am::length_to_steps(125, 40000, steps));  // 0.0125 mm * 40 = 0.5 step
  EXPECT_EQ(steps, 1);
  ASSERT_TRUE(am::length_to_steps(-125, 40000, steps));
  EXPECT_EQ(steps, -1);
  // Overflow is refused, the output untouched.
  steps = 9;
  EXPECT_FALSE(am::length_to_steps(am::kFixedMax, 100000000, steps));  // 214 m at 100000 steps/mm
  EXPECT_EQ(steps, 9);
  ASSERT_TRUE(am::inch_to_length(84546600, v));  // 8454.66 in = 214748.3640 mm
  EXPECT_EQ(v, 2147483640);
  v = 3;
  EXPECT_FALSE(am::inch_to_length(84546601, v));  // 214748.36654 mm
  EXPECT_FALSE(am::inch_to_length(-84546601, v));
  EXPECT_EQ(v, 3);
}

TEST(FixedNumber, ConversionsMatchExactRationalArithmetic) {
  std::mt19937 rng(9);
  const uint32_t scales[] = {1, 4096, 25000, 80000, 93000, 100000, 400000, 1000000, 1600000, 3200000, 96275,
                             4294967295u};
  for (int n = 0; n < 20000; ++n) {
    const int32_t len = int32_t(rng()) >> (rng() % 31);
    const uint32_t spm = scales[rng() % (sizeof scales / sizeof scales[0])];
    const __int128 num = __int128(len < 0 ? -__int128(len) : __int128(len)) * spm;
    __int128 q = (num * 2 + 10000000) / 20000000;  // round half up on the magnitude
    if (len < 0) q = -q;
    int32_t steps = 12345;
    const bool ok = am::length_to_steps(len, spm, steps);
    if (q > am::kFixedMax || q < -__int128(am::kFixedMax)) {
      EXPECT_FALSE(ok) << len << " " << spm;
      EXPECT_EQ(steps, 12345);
    } else {
      ASSERT_TRUE(ok) << len << " " << spm;
      EXPECT_EQ(__int128(steps), q) << len << " " << spm;
    }
    // And back: steps -> length.
    const int32_t st = int32_t(rng()) >> (8 + rng() % 23);
    const __int128 n2 = __int128(st < 0 ? -__int128(st) : __int128(st)) * 10000000;
    __int128 back = (n2 * 2 + spm) / (__int128(spm) * 2);
    if (st < 0) back = -back;
    int32_t length = 0;
    const bool ok2 = am::steps_to_length(st, spm, length);
    if (back > am::kFixedMax || back < -__int128(am::kFixedMax)) EXPECT_FALSE(ok2);
    else if (ok2) EXPECT_EQ(__int128(length), back) << st << " " << spm;
    else ADD_FAILURE() << st << " " << spm;
  }
  int32_t out = 0;
  EXPECT_FALSE(am::steps_to_length(5, 0, out));
}

TEST(FixedNumber, FormatMatchesPrintf) {
  std::mt19937 rng(10);
  char buf[13];
  char ref[32];
  for (int n = 0; n < 5000; ++n) {
    const int32_t v = int32_t(rng()) >> (rng() % 31);
    if (v == INT32_MIN) continue;
    const uint8_t d = uint8_t(rng() % 10);
    const uint8_t len = am::format_fixed(buf, v, d);
    long long p10 = 1;
    for (int k = 0; k < d; ++k) p10 *= 10;
    const long long mag = v < 0 ? -(long long)v : v;
    if (d == 0) std::snprintf(ref, sizeof ref, "%s%lld", v < 0 ? "-" : "", mag);
    else std::snprintf(ref, sizeof ref, "%s%lld.%0*lld", v < 0 ? "-" : "", mag / p10, int(d), mag % p10);
    EXPECT_STREQ(buf, ref);
    EXPECT_EQ(len, std::string(ref).size());
  }
  am::format_fixed(buf, -am::kFixedMax, 4);
  EXPECT_STREQ(buf, "-214748.3647");
  am::format_fixed(buf, 5, 4);
  EXPECT_STREQ(buf, "0.0005");
}
