// The seed's B(n) list, produced by the Follower.
//
// Contract
//   B(n) = floor(n lambda) - floor((n - 1) lambda), n = 1, 2, ...: the
//   leadscrew counts issued on the n-th forward spindle count after a reset
//   with no phase. Every B(n) is floor(lambda) or floor(lambda) + 1 and the
//   sequence repeats with period den / gcd(num, den), one period summing to
//   num / gcd(num, den).
//   bn_list() writes B(1) .. B(count) and returns the period.
//
// Why it exists: the seed precomputed one period of this sequence into a
// circular list (one node per denominator unit, which is what forced its
// denominators down to 150) and fed one element per spindle pulse into the
// servo's position error. avrmotion does not store it: the Follower yields
// the same numbers with 28 bytes of state. This header regenerates the list
// from the Follower so the host tests can hold it against the seed's
// published vectors, i.e. the accumulator and the seed's table agree term by
// term. Host or main-loop use only (one Follower step per element).
#pragma once
#include <stdint.h>

#include "follower.h"
#include "rational.h"

namespace am {

template <typename T>
inline uint32_t bn_list(const Ratio& r, T* out, uint32_t count) {
  Follower f;
  if (!f.reset(r, false)) return 0;
  int32_t last = f.position();
  for (uint32_t i = 0; i < count; ++i) {
    f.advance();
    out[i] = T(f.position() - last);
    last = f.position();
  }
  return r.den / gcd32(r.num, r.den);
}

}  // namespace am
