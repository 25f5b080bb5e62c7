// Integer square roots (bit-by-bit, no division), for planners that must give
// the same answer on the AVR and on the host.
#pragma once
#include <stdint.h>

namespace am {

// floor(sqrt(x))
inline uint32_t isqrt64(uint64_t x) {
  uint64_t result = 0;
  uint64_t bit = uint64_t(1) << 62;
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
  return uint32_t(result);
}

// floor(sqrt(x)) in 32-bit arithmetic: four times cheaper than isqrt64 on
// the AVR, where 64-bit shifts and compares are library calls.
inline uint16_t isqrt32(uint32_t x) {
  uint32_t result = 0;
  uint32_t bit = uint32_t(1) << 30;
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
  return uint16_t(result);
}

}  // namespace am
