// Natural logarithm and exponential as constexpr functions, so tables of
// physical curves (the thermistor table) are computed by the compiler and
// stored in the image, with no generator tool and no code at run time.
//
// Contract
//   const_ln(x) for x > 0, const_exp(x) for x within the format's range. They
//   are evaluated at compile time in the target's double: 64-bit on the host,
//   32-bit on avr-gcc (its double is float), and are accurate to a few units
//   in the last place of that format (tests/host/test_thermal_thermistor.cpp
//   compares them with <cmath> on the host). A non-positive or infinite
//   argument to const_ln divides 0 by 0: a compile error in a constant
//   expression, a NaN at run time.
//
//   Why our own: avr-gcc 5.4 has no C++ standard library, and <cmath> is not
//   constexpr anyway. Not meant for run time on the AVR, where every double
//   operation is a software-float call.
#pragma once

namespace am {

namespace const_math_detail {
constexpr double kLn2 = 0.693147180559945309417;
// ln 2 split so that k * kLn2Hi is exact for |k| < 2^11 (Cody and Waite).
constexpr double kLn2Hi = 6.93147180369123816490e-01, kLn2Lo = 1.90821492927058770002e-10;
constexpr double kSqrt2 = 1.41421356237309504880;
}  // namespace const_math_detail

constexpr double const_ln(double x) {
  using namespace const_math_detail;
  if (!(x > 0) || x - x != 0) return (x - x) / (x - x);  // x <= 0, inf, NaN: not a constant
  // x = m 2^k with m in [1/sqrt2, sqrt2): scaling by 2 is exact.
  int k = 0;
  while (x >= kSqrt2) { x *= 0.5; ++k; }
  while (x < kSqrt2 / 2) { x *= 2; --k; }
  // ln m = 2 atanh(s) = 2 (s + s^3/3 + s^5/5 + ...), s = (m - 1)/(m + 1),
  // |s| <= 0.172: each term is 34 times smaller than the one before.
  const double s = (x - 1) / (x + 1), s2 = s * s;
  double term = s, sum = 0;
  for (int n = 1; n < 32; n += 2) {
    sum += term / n;
    term *= s2;
  }
  return 2 * sum + k * kLn2;
}

constexpr double const_exp(double x) {
  using namespace const_math_detail;
  // x = k ln2 + r with |r| <= ln2 / 2, exp x = 2^k exp r (Taylor series).
  const int k = int(x / kLn2 + (x < 0 ? -0.5 : 0.5));
  const double r = (x - k * kLn2Hi) - k * kLn2Lo;
  double term = 1, sum = 1;
  for (int n = 1; n < 24; ++n) {
    term *= r / n;
    sum += term;
  }
  for (int i = 0; i < k; ++i) sum *= 2;
  for (int i = 0; i > k; --i) sum *= 0.5;
  return sum;
}

}  // namespace am
