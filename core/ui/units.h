// The operator panel's numbers in the leadscrew's units (workflow.h uses
// them): a length or move in um becomes steps as floor(um x counts per turn
// / lead) (toward zero for negatives); a carriage position in steps shows as
// floor(steps x lead / counts) um; both exact in 128 bits (core/lathe/
// wide.h), so nothing rounds twice, and saturated to +-(2^31 - 1).
#pragma once
#include <stdint.h>

#include "../lathe/ratio.h"

namespace am {
namespace ui {

// v m / d, the magnitude floored, saturated to +-(2^31 - 1); d > 0.
__attribute__((noinline)) inline int32_t scale(int32_t v, uint32_t m, uint32_t d) {
  U128 x = u128(v < 0 ? uint32_t(0) - uint32_t(v) : uint32_t(v)), rem;
  mul_small(x, m);
  divmod(x, u128(d), x, rem);
  const int32_t mag = (!fits32(x) || x.w[0] > 0x7FFFFFFFu) ? 0x7FFFFFFF : int32_t(x.w[0]);
  return v < 0 ? -mag : mag;
}

// The settings' machines have whole counts per turn (below 2^21.3) and a
// lead's denominator of at most 1000 (0.1 TPI), so both products fit 32 bits.
__attribute__((noinline)) inline int32_t um_to_steps(const Machine& m, int32_t um) {
  return scale(um, m.leadscrew_counts.num * m.leadscrew.den, m.leadscrew.num);
}

inline int32_t steps_to_um(const Machine& m, int32_t steps) {
  return scale(steps, m.leadscrew.num, m.leadscrew.den * m.leadscrew_counts.num);
}

}  // namespace ui
}  // namespace am
