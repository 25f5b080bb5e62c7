// 128-bit unsigned integers for the gear-ratio set-up (main loop only).
//
// Contract
//   U128 is four 32-bit limbs, least significant first. mul_small()
//   multiplies by a 32-bit number, sub() subtracts, cmp() compares, divmod()
//   divides by any nonzero U128 (floor quotient and remainder). That is all
//   the set-up needs: exact products of the ratio's factors, the Euclid steps
//   of the continued fraction, cross products of up to 96 bits, and the pitch
//   error as one product divided by three denominators in turn
//   (floor(floor(x / a) / b) = floor(x / (a b)) for positive integers, so the
//   chain loses nothing).
//
// Why limbs and not uint64_t / unsigned __int128: avr-gcc has no 128-bit
// type, and its inline 64-bit code is large (register shuffling and spills
// for every operator): the same set-up written with uint64_t took about 9 KB
// of flash. Four loops over 32-bit limbs, each emitted once, are a fraction
// of that, and the host tests run exactly this code.
//
// Cost: divmod() is restoring division, one round per significant bit of the
// dividend (whole zero limbs are skipped), each round a 128-bit shift, compare
// and subtract; fine once per ratio change, never per spindle edge.
#pragma once
#include <stdint.h>

namespace am {

struct U128 {
  uint32_t w[4];
};

constexpr U128 u128(uint32_t v) { return {{v, 0, 0, 0}}; }
inline U128 u128_64(uint64_t v) { return {{uint32_t(v), uint32_t(v >> 32), 0, 0}}; }
inline uint64_t low64(const U128& x) { return x.w[0] | (uint64_t(x.w[1]) << 32); }
inline bool is_zero(const U128& x) { return (x.w[0] | x.w[1] | x.w[2] | x.w[3]) == 0; }
inline bool fits32(const U128& x) { return (x.w[1] | x.w[2] | x.w[3]) == 0; }
inline bool fits64(const U128& x) { return (x.w[2] | x.w[3]) == 0; }

// x *= m modulo 2^128; returns the part that did not fit (0: exact).
__attribute__((noinline)) inline uint32_t mul_small(U128& x, uint32_t m) {
  uint32_t carry = 0;
  for (uint8_t i = 0; i < 4; ++i) {
    const uint64_t t = uint64_t(x.w[i]) * m + carry;
    x.w[i] = uint32_t(t);
    carry = uint32_t(t >> 32);
  }
  return carry;
}

// a -= b modulo 2^128; returns true on a borrow (a was below b).
__attribute__((noinline)) inline bool sub(U128& a, const U128& b) {
  bool borrow = false;
  for (uint8_t i = 0; i < 4; ++i) {
    const uint32_t ai = a.w[i], bi = b.w[i];
    const uint32_t d = ai - bi - (borrow ? 1u : 0u);
    borrow = ai < bi || (borrow && ai == bi);
    a.w[i] = d;
  }
  return borrow;
}

// -1, 0, 1 as a <, ==, > b.
__attribute__((noinline)) inline int8_t cmp(const U128& a, const U128& b) {
  for (uint8_t i = 4; i-- > 0;)
    if (a.w[i] != b.w[i]) return a.w[i] < b.w[i] ? -1 : 1;
  return 0;
}

// q = floor(n / d), rem = n mod d; d != 0. q may be n itself.
__attribute__((noinline)) inline void divmod(const U128& n, const U128& d, U128& q, U128& rem) {
  q = n;
  rem = u128(0);
  uint8_t rounds = 128;
  while (rounds > 0 && q.w[3] == 0) {  // skip whole zero limbs of the dividend
    q.w[3] = q.w[2], q.w[2] = q.w[1], q.w[1] = q.w[0], q.w[0] = 0;
    rounds = uint8_t(rounds - 32);
  }
  while (rounds-- > 0) {
    // rem:q <<= 1 (a 256-bit shift); a bit out of rem means rem >= d.
    const bool out = (rem.w[3] >> 31) != 0;
    for (uint8_t i = 4; i-- > 0;) rem.w[i] = (rem.w[i] << 1) | (i ? rem.w[i - 1] >> 31 : q.w[3] >> 31);
    for (uint8_t i = 4; i-- > 0;) q.w[i] = (q.w[i] << 1) | (i ? q.w[i - 1] >> 31 : 0u);
    if (out || cmp(rem, d) >= 0) {
      sub(rem, d);  // modulo 2^128: exact, the true difference is below d
      q.w[0] |= 1;
    }
  }
}

}  // namespace am
