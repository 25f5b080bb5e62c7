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

}  // namespace am
