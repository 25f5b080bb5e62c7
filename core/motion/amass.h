// Multi-axis smoothing at low rates (after grbl's AMASS): a coordinated
// block whose minor axes would step on a coarse grid runs 2^L events per
// step of its dominant axis instead of one.
//
// Why
//   In a coordinated block the interrupt runs one event per interval and
//   every axis steps only at events (core/motion/line_dda.h). With one event
//   per dominant step, a minor axis's step waits for the next dominant step:
//   at 160 steps/s that is up to 6 ms after the straight line crosses it,
//   and its intervals alternate between one and two dominant intervals (a
//   buzz at low feeds). With 2^L events per dominant step the minor waits at
//   most 1/2^L of a dominant interval.
//
// Contract
//   level(events, cruise, event_cap) is the largest L <= kMaxLevel such
//   that the block's events at its cruise speed (events/s, rounded
//   down), cruise 2^L, stay within event_cap events/s and events 2^L within kMaxEvents (the trapezoid's
//   limit); 0 when even L = 1 does not fit. A block run at level L is the
//   same motion counted in finer events: its TrapezoidBlock's events,
//   speeds and acceleration all multiplied by 2^L (scale(), exact in float:
//   a power of two), its interpolator started over events 2^L with every
//   axis a minor in DdaPhase::late, so axis i's k-th step comes at event
//   ceil(k N 2^L / n_i): the dominant axis's exactly on its k 2^L-th event,
//   that is on the time of the unsmoothed profile's k-th event, and every
//   other axis at the first event at or after the straight line crosses its
//   step, under 1/2^L of a dominant interval late. A block without minor
//   axes (a diagonal) is smoothed too: it costs it only interrupts, and a
//   test for it more flash than the smoothing itself.
//   The price: 2^L interrupts per dominant step, within event_cap.
#pragma once
#include <stddef.h>
#include <stdint.h>

#include "trapezoid.h"

namespace am {
namespace amass {

constexpr uint8_t kMaxLevel = 3;  // grbl's: minors at most 1/8 interval late
constexpr uint32_t kMaxEvents = uint32_t(1) << 24;

inline uint8_t level(uint32_t events, uint32_t cruise, uint32_t event_cap) {
  uint8_t l = 0;
  uint32_t most = kMaxEvents;
  while (l < kMaxLevel && cruise <= (event_cap >>= 1) && events <= (most >>= 1)) ++l;
  return l;
}

// Multiplies the block's events, speeds and acceleration by 2^l in place.
// On a float's bits: 2^l times a positive normal float adds l to its
// exponent (exactly the product), 0 stays 0; the exponent sits in the upper
// 16 bits, so 16-bit arithmetic does it (for less flash than four float
// multiplications). The speeds are 0 or normal floats (a denormal would be
// under 1e-38 events/s).
inline void scale(TrapezoidBlock& b, uint8_t l) {
  static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "the upper half of a float is its second uint16_t");
  static_assert(offsetof(TrapezoidBlock, accel) - offsetof(TrapezoidBlock, entry) == 3 * sizeof(float),
                "entry, cruise, exit, accel follow each other");
  b.events <<= l;
  typedef uint16_t __attribute__((may_alias)) Half;
  Half* upper = reinterpret_cast<Half*>(&b.entry) + 1;
  const uint16_t step = uint16_t(l << 7);
  for (uint8_t i = 0; i < 4; ++i, upper += 2)
    if (*upper) *upper = uint16_t(*upper + step);
}

}  // namespace amass
}  // namespace am
