// Best rational approximation under bounds on numerator and denominator, by
// continued fractions; and gcd.
//
// Contract
//   best_rational(N, D, max_num, max_den) returns the fraction p/q with
//   p <= max_num and 1 <= q <= max_den (32-bit bounds, both >= 1) nearest to
//   N/D (0 <= N < 2^64, 1 <= D < 2^64, so the cross products below fit);
//   among equally near ones, the one with the smaller denominator. When N/D
//   itself fits (after reduction) it is returned, reduced. The result also
//   carries e = p D - q N exactly, as a magnitude and a sign:
//   p/q - N/D = e / (q D), the input the caller needs for an exact error.
//
// Why continued fractions: the fractions with p <= P and q <= Q are closed
// under taking Stern-Brocot ancestors, so the two members nearest to N/D on
// either side are the last convergent that fits and the semiconvergent
// (p_{k-2} + j p_{k-1}) / (q_{k-2} + j q_{k-1}) with the largest j that fits.
// Only those two are compared; no search over denominators. Each step is one
// wide division (about 90 steps at most for 64-bit inputs).
//
// Bookkeeping: with r_{-2} = N, r_{-1} = D, r_k = r_{k-2} - a_k r_{k-1} (the
// Euclid remainders), convergent k has |q_k N - p_k D| = r_k and sign
// p_k D - q_k N = (-1)^(k+1) r_k; the semiconvergent between convergents k-2
// and k-1 has |e| = r_{k-2} - j r_{k-1} with the sign of convergent k-2.
#pragma once
#include <stdint.h>

#include "wide.h"

namespace am {

__attribute__((noinline)) inline uint32_t gcd32(uint32_t a, uint32_t b) {
  while (b != 0) {
    const uint32_t t = a % b;
    a = b;
    b = t;
  }
  return a;
}

struct Approximation {
  uint32_t num;
  uint32_t den;
  U128 error;           // |p D - q N|
  bool error_positive;  // p/q > N/D
};

// The bounds are 32-bit, so every convergent that fits is 32-bit too; only
// the Euclid remainders and partial quotients are wide. The remainders live
// in three buffers that rotate by pointer (the AVR pays for every 16-byte
// copy).
inline Approximation best_rational(const U128& N, const U128& D, uint32_t max_num, uint32_t max_den) {
  U128 buf[3] = {N, D, u128(0)};
  U128 *x = &buf[0], *y = &buf[1], *r = &buf[2];  // r_{k-2}, r_{k-1}, r_k
  U128 a;
  uint32_t p0 = 0, q0 = 1;  // convergent k-2 (starts as 0/1)
  uint32_t p1 = 1, q1 = 0;  // convergent k-1 (starts as 1/0)
  bool k_odd = false;       // parity of the index k of the convergent being formed
  uint32_t jmax;
  for (;;) {
    jmax = 0xFFFFFFFFu;
    if (q1 != 0) jmax = (max_den - q0) / q1;
    if (p1 != 0) {
      const uint32_t jn = (max_num - p0) / p1;
      if (jn < jmax) jmax = jn;
    }
    divmod(*x, *y, a, *r);  // a_k = r_{k-2} / r_{k-1}, r_k = r_{k-2} mod r_{k-1}
    if (!fits32(a) || a.w[0] > jmax) break;
    const uint32_t p2 = a.w[0] * p1 + p0, q2 = a.w[0] * q1 + q0;
    p0 = p1, q0 = q1, p1 = p2, q1 = q2;
    U128* t = x;
    x = y, y = r, r = t;
    if (is_zero(*y)) return {p1, q1, u128(0), false};
    k_odd = !k_odd;
  }
  // Convergent k-1 (|e| = r_{k-1}, sign (-1)^k) against the semiconvergent
  // with j = jmax < a_k (|e| = r_{k-2} - jmax r_{k-1}, sign (-1)^(k-1)).
  const uint32_t ps = p0 + jmax * p1, qs = q0 + jmax * q1;
  *r = *y;
  mul_small(*r, jmax);
  sub(*x, *r);  // x: the semiconvergent's |e|
  bool take_semi;
  if (q1 == 0) {
    take_semi = true;  // k = 0: only integers can fit
  } else if (qs == 0) {
    take_semi = false;  // k = 1 with j = 0 would be 1/0
  } else {
    // |e_s| / q_s < |e_c| / q_c  <=>  e_s q_c < e_c q_s (no overflow: the
    // errors are Euclid remainders, below 2^64 for 64-bit N and D).
    a = *x;
    mul_small(a, q1);
    *r = *y;
    mul_small(*r, qs);
    const int8_t order = cmp(a, *r);
    take_semi = order < 0 || (order == 0 && qs < q1);
  }
  if (take_semi) return {ps, qs, *x, k_odd};
  return {p1, q1, *y, !k_odd};
}

}  // namespace am
