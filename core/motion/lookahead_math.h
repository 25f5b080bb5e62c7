// Integer helpers of the look-ahead planner (core/motion/lookahead.h): bit
// lengths, divisions and square roots with 32-bit fast paths, and a small
// mantissa/exponent number for the junction formula. Integers only, so the
// AVR and the host compute the same bits.
//
// Contract
//   abs32(v)          |v| for any int32 except INT32_MIN (callers refuse it).
//   bit_length32(x), bit_length(x)
//                     number of significant bits (0 for 0).
//   div_u64(n, d)     floor(n / d), d >= 1; a 32-bit division when n and d
//                     fit 32 bits.
//   isqrt_approx(x)   floor(sqrt(x >> 2k)) << k with the smallest k that
//                     makes x >> 2k fit 32 bits: exact below 2^32, never
//                     above the root, within 2^-15 of it (relative) above.
//   isqrt_exact(x)    floor(sqrt(x)) for any uint64.
//   norm24(x, n, r)   for x in [2^30, 2^32): n = sqrt(x) 2^8 (24 bits) and
//                     r = 2^48 / n, both within about 2^-23, from isqrt32(),
//                     one 32-bit division and 32-bit products.
//   Fp16              m 2^e with m in [2^15, 2^16) (or m = 0: zero): every
//                     operation (fp_make, fp_mul, fp_div, fp_add) truncates
//                     to 16 significant bits, i.e. is within 2^-15 below the
//                     exact result; fp_less compares; fp_to_u64(a, cap) is
//                     min(cap, floor(a)).
//
// Why
//   Measured on the ATmega32 in simavr (avr-gcc 5.4 -Os): a 64-bit division
//   costs 800 .. 1900 cycles, a 32-bit one 630, 32 x 32 -> 64 bit products
//   230, 16 x 16 -> 32 bit products 60, a variable 64-bit shift about 150, the
//   library's bitwise isqrt64() 7600 and isqrt32() 610. So the planner keeps
//   operands in 32 bits where they fit, takes 64-bit square roots from a
//   32-bit one (and one Newton step where the exact root matters), and does
//   the junction formula, which needs 4 significant digits and a huge range,
//   in Fp16: one 32-bit division and 16 x 16 bit products.
#pragma once
#include <stdint.h>

#include "../math/isqrt.h"

namespace am {
namespace lookahead_detail {

inline uint32_t abs32(int32_t v) { return v < 0 ? 0u - uint32_t(v) : uint32_t(v); }

// The halves of a uint64 and back (avr-gcc turns a constant 64-bit shift
// into a loop; a union is register moves).
inline uint32_t hi32(uint64_t x) {
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
  union {
    uint64_t v;
    uint32_t w[2];
  } u;
  u.v = x;
  return u.w[1];
#else
  return uint32_t(x >> 32);
#endif
}

inline uint64_t make64(uint32_t lo, uint32_t hi) {
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
  union {
    uint64_t v;
    uint32_t w[2];
  } u;
  u.w[0] = lo;
  u.w[1] = hi;
  return u.v;
#else
  return uint64_t(hi) << 32 | lo;
#endif
}

inline uint8_t bit_length32(uint32_t x) {
  uint8_t n = 0;
  if (x >> 16) {
    x >>= 16;
    n = 16;
  }
  uint16_t y = uint16_t(x);
  if (y >> 8) {
    y = uint16_t(y >> 8);
    n = uint8_t(n + 8);
  }
  uint8_t z = uint8_t(y);
  while (z) {
    z = uint8_t(z >> 1);
    ++n;
  }
  return n;
}

inline uint8_t bit_length(uint64_t x) {
  const uint32_t hi = hi32(x);
  return hi ? uint8_t(32 + bit_length32(hi)) : bit_length32(uint32_t(x));
}

// x >> n and x << n for 0 <= n <= 31, by 16 and 8 bits at a time (avr-gcc
// shifts a uint32 one bit per loop turn).
inline uint32_t shr32(uint32_t x, uint8_t n) {
  if (n & 16) x >>= 16;
  if (n & 8) x >>= 8;
  for (n &= 7; n; --n) x >>= 1;
  return x;
}
inline uint32_t shl32(uint32_t x, uint8_t n) {
  if (n & 16) x <<= 16;
  if (n & 8) x <<= 8;
  for (n &= 7; n; --n) x <<= 1;
  return x;
}

// x >> s for a result known to fit 32 bits, 0 <= s <= 63.
inline uint32_t shr_to32(uint64_t x, uint8_t s) {
  const uint32_t hi = hi32(x), lo = uint32_t(x);
  if (s >= 32) return shr32(hi, uint8_t(s - 32));
  if (s == 0) return lo;
  return shr32(lo, s) | shl32(hi, uint8_t(32 - s));
}

__attribute__((noinline)) inline uint64_t div_u64(uint64_t n, uint64_t d) {
  if (hi32(n) == 0 && hi32(d) == 0) return uint32_t(n) / uint32_t(d);
  return n / d;
}

__attribute__((noinline)) inline uint32_t isqrt_approx(uint64_t x) {
  const uint32_t hi = hi32(x);
  if (hi == 0) return isqrt32(uint32_t(x));
  // The even shift that brings x into [2^30, 2^32).
  const uint8_t s = uint8_t((bit_length32(hi) + 1) & ~1u);
  return shl32(isqrt32(shr_to32(x, s)), uint8_t(s / 2));
}

__attribute__((noinline)) inline uint32_t isqrt_exact(uint64_t x) {
  if (hi32(x) == 0) return isqrt32(uint32_t(x));
  // r0 <= sqrt(x) < r0 (1 + 2^-15); one Newton step leaves the root at most
  // one below or about two above floor(sqrt(x)).
  const uint32_t r0 = isqrt_approx(x);
  const uint64_t t = (uint64_t(r0) + x / r0) >> 1;
  uint32_t r = hi32(t) ? 0xFFFFFFFFu : uint32_t(t);
  while (uint64_t(r) * r > x) --r;
  while (r != 0xFFFFFFFFu && uint64_t(r + 1) * (r + 1) <= x) ++r;
  return r;
}

// sqrt(x) 2^8 and 2^48 / that, for x in [2^30, 2^32). With r16 =
// isqrt32(x), rem = x - r16^2 and q = (2^32 - 1) / r16 (remainder qrem):
//   sqrt(x) ~ r16 + rem / (2 r16)         (first order, error < 2^-16)
//   2^40 / r16 ~ 2^8 q + 2^8 qrem / r16   (q's own remainder)
//   2^48 / n ~ (2^40 / r16) (1 - f / (2^8 r16)),  n = 2^8 r16 + f
// where every 1 / r16 is q / 2^32: each correction is below 2^-15 of its
// value, so that approximation costs under 2^-30.
__attribute__((noinline)) inline void norm24(uint32_t x, uint32_t& n, uint32_t& r) {
  // 16 x 16 bit products and shifts by 16 (a word move): avr-gcc shifts a
  // uint32 by other constants one bit per loop turn.
  const uint16_t r16 = isqrt32(x);                    // [2^15, 2^16)
  const uint32_t rem = x - uint32_t(r16) * r16;        // [0, 2 r16]
  const uint32_t q = 0xFFFFFFFFu / r16;               // (2^16, 2^17)
  const uint16_t qrem = uint16_t(0xFFFFFFFFu % r16);
  const uint16_t q1 = uint16_t(q >> 1);
  // rem / (2 r16) in Q8 = rem q / 2^25 (<= 256).
  const uint16_t f = uint16_t(uint16_t((uint32_t(uint16_t(rem >> 1)) * q1) >> 16) >> 7);
  n = (uint32_t(r16) << 8) + f;
  // 2^40 / r16 = 2^8 q + qrem q / 2^24, in (2^24, 2^25].
  const uint32_t r1 = (q << 8) + (uint16_t((uint32_t(qrem) * q1) >> 16) >> 7);
  // r1 f / (2^8 r16) = r1 f q / 2^40 (< 2^10).
  const uint16_t t = uint16_t((uint32_t(uint16_t(r1 >> 10)) * f) >> 8);
  r = r1 - (uint16_t((uint32_t(t) * uint16_t(q >> 2)) >> 16) >> 4);
}

struct Fp16 {
  uint16_t m;  // 0, or in [2^15, 2^16)
  int16_t e;
};

__attribute__((noinline)) inline Fp16 fp_make(uint32_t x, int16_t e) {
  // A byte, then at most 8 single bits, either way.
  if (x >> 16) {
    if (x >> 24) {
      x >>= 8;
      e = int16_t(e + 8);
    }
    while (x >> 16) {
      x >>= 1;
      ++e;
    }
    return Fp16{uint16_t(x), e};
  }
  uint16_t y = uint16_t(x);
  if (y == 0) return Fp16{0, 0};
  if (!(y >> 8)) {
    y = uint16_t(y << 8);
    e = int16_t(e - 8);
  }
  while (!(y & 0x8000u)) {
    y = uint16_t(y << 1);
    --e;
  }
  return Fp16{y, e};
}

inline Fp16 fp_make64(uint64_t x, int16_t e) {
  const uint8_t b = bit_length(x);
  return b > 32 ? fp_make(shr_to32(x, uint8_t(b - 32)), int16_t(e + (b - 32))) : fp_make(uint32_t(x), e);
}

__attribute__((noinline)) inline Fp16 fp_mul(Fp16 a, Fp16 b) {
  const uint32_t p = uint32_t(a.m) * b.m;  // [2^30, 2^32) or 0
  if (p == 0) return Fp16{0, 0};
  const uint16_t top = uint16_t(p >> 16);
  if (top & 0x8000u) return Fp16{top, int16_t(a.e + b.e + 16)};
  return Fp16{uint16_t(top << 1 | ((uint16_t(p) & 0x8000u) ? 1u : 0u)), int16_t(a.e + b.e + 15)};
}

// a / b, b != 0.
__attribute__((noinline)) inline Fp16 fp_div(Fp16 a, Fp16 b) {
  if (a.m == 0) return a;
  const uint32_t q = (uint32_t(a.m) << 16) / b.m;  // (2^15, 2^17)
  if (uint16_t(q >> 16)) return Fp16{uint16_t(q >> 1), int16_t(a.e - b.e - 15)};
  return Fp16{uint16_t(q), int16_t(a.e - b.e - 16)};
}

__attribute__((noinline)) inline Fp16 fp_add(Fp16 a, Fp16 b) {
  if (b.m == 0) return a;
  if (a.m == 0) return b;
  if (a.e < b.e) {
    const Fp16 t = a;
    a = b;
    b = t;
  }
  const int16_t diff = int16_t(a.e - b.e);
  const uint32_t sum = uint32_t(a.m) + (diff < 16 ? uint32_t(b.m >> diff) : 0u);
  return fp_make(sum, a.e);
}

inline bool fp_less(Fp16 a, Fp16 b) {
  if (a.m == 0 || b.m == 0) return a.m < b.m;
  return a.e != b.e ? a.e < b.e : a.m < b.m;
}

__attribute__((noinline)) inline uint64_t fp_to_u64(Fp16 a, uint64_t cap) {
  if (a.m == 0) return 0;
  if (a.e >= 0) {
    if (a.e >= 48) return cap;  // >= 2^63
    const uint64_t v = uint64_t(a.m) << a.e;
    return v < cap ? v : cap;
  }
  const uint32_t v = a.e <= -16 ? 0u : shr32(a.m, uint8_t(-a.e));
  return v < cap ? v : cap;
}

}  // namespace lookahead_detail
}  // namespace am
