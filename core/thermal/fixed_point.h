// Integer helpers for the heater core's fixed-point arithmetic: a scaled
// product without 64-bit operations, and clamping.
//
// Contract
//   mul_div_round(a, b, c) = a * b / c rounded to nearest (halves up), for
//   1 <= c <= 2^31 and a true result below 2^32. It works on the 64-bit
//   product a * b as quotient and remainder by c, one bit of b at a time, so
//   it needs only 32-bit shifts, adds and compares and no 64-bit libgcc
//   routines (with avr-gcc 5.4 -Os it is about 160 bytes smaller than the
//   same expression in uint64_t). It is meant for configuration time (gain
//   conversion, autotune results): 32 rounds of a loop, about 5500 cycles
//   on the AVR.
#pragma once
#include <stdint.h>

namespace am {

constexpr uint32_t mul_div_round(uint32_t a, uint32_t b, uint32_t c) {
  // a = qa c + ra; invariant: (processed high bits of b) * a = q c + r, r < c.
  const uint32_t qa = a / c, ra = a % c;
  uint32_t q = 0, r = 0;
  for (int8_t bit = 31; bit >= 0; --bit) {
    q <<= 1;
    r <<= 1;  // r < c <= 2^31: no overflow
    if (r >= c) { r -= c; ++q; }
    if ((b >> bit) & 1u) {
      q += qa;
      r += ra;  // < 2c <= 2^32
      if (r >= c) { r -= c; ++q; }
    }
  }
  if (r >= c - r) ++q;  // 2r >= c, without forming 2r
  return q;
}

constexpr int32_t clamp32(int32_t x, int32_t lo, int32_t hi) { return x < lo ? lo : x > hi ? hi : x; }

}  // namespace am
