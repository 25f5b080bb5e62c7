// Integer square roots (bit-by-bit, no division), for planners that must give
// the same answer on the AVR and on the host.
#pragma once
#include <stdint.h>

namespace am {

// floor(sqrt(x)), bit by bit: shifts, compares and subtractions only, in
// the width of T (the narrowest that holds x is the cheapest on the AVR,
// where 64-bit shifts and compares are library calls).
template <typename T>
inline T isqrt_bitwise(T x) {
  T result = 0;
  T bit = T(1) << (8 * sizeof(T) - 2);
  while (bit > x) bit >>= 2;
  while (bit != 0) {
    if (x >= result + bit) {
      x -= result + bit;
      result = (result >> 1) + bit;
    } else {
      result >>= 1;
    }
    bit >>= 2;
  }
  return result;
}

inline uint32_t isqrt64(uint64_t x) { return uint32_t(isqrt_bitwise<uint64_t>(x)); }
inline uint16_t isqrt32(uint32_t x) { return uint16_t(isqrt_bitwise<uint32_t>(x)); }

}  // namespace am
