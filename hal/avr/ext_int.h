// External interrupts INT0 and INT1: the step input of the driver board,
// the lathe's spindle encoder, and edge latches for the endstops
// (firmware/axes/endstops.h).
//
// Contract
//   enable_int0_rising() makes every rising edge on INT0 raise INT0_vect:
//   ISC01:ISC00 = 11 (datasheet "External Interrupts", table "Interrupt 0 Sense
//   Control"), a flag left from before is cleared first so no stale edge is
//   taken, then INT0 is unmasked. The pin itself stays as the caller configured
//   it (input, with or without pull-up). The ISR is the caller's.
//
//   enable_int0(sense) / enable_int1(sense) do the same for INT0 / INT1 with
//   any change, a falling or a rising edge (ISCx1:ISCx0 = 01, 10, 11); the
//   other line's sense bits are left as they are. disable_int0/1() mask the
//   line and drop a latched edge.
//
//   Edge interrupts are latched in INTF0: an edge that arrives while the ISR
//   (or any other) runs is kept and served afterwards, but a second edge
//   before that is lost (one flag, no counter), which bounds the step rate.
//
//   latch_edges(line, rising) makes INTFn latch each rising (or falling)
//   edge on INTn without raising any interrupt (INTn stays masked);
//   latched() reads the flags, clear_latched(flags) clears them (one write).
//   Flag masks are _BV(INTF0), _BV(INTF1) (latch_flag(line)).
//
//   ATmega16/32 keep the bits in MCUCR/GICR/GIFR; the ATmega328P in
//   EICRA/EIMSK/EIFR with the same bit names.
#pragma once
#include <stdint.h>
#include "family.h"

namespace hal {
namespace ext_int {

#if defined(GICR)
#define HAL_EXTINT_SENSE MCUCR
#define HAL_EXTINT_MASK GICR
#define HAL_EXTINT_FLAGS GIFR
#else
#define HAL_EXTINT_SENSE EICRA
#define HAL_EXTINT_MASK EIMSK
#define HAL_EXTINT_FLAGS EIFR
#endif

inline void enable_int0_rising() {
  HAL_EXTINT_MASK &= uint8_t(~_BV(INT0));  // no interrupt while the sense changes
  HAL_EXTINT_SENSE |= _BV(ISC01) | _BV(ISC00);
  HAL_EXTINT_FLAGS = _BV(INTF0);           // write one to clear
  HAL_EXTINT_MASK |= _BV(INT0);
}

enum class Sense : uint8_t { any_change = 1, falling = 2, rising = 3 };

inline void enable_int0(Sense s) {
  HAL_EXTINT_MASK &= uint8_t(~_BV(INT0));
  HAL_EXTINT_SENSE = uint8_t((HAL_EXTINT_SENSE & ~(_BV(ISC01) | _BV(ISC00))) | (uint8_t(s) << ISC00));
  HAL_EXTINT_FLAGS = _BV(INTF0);
  HAL_EXTINT_MASK |= _BV(INT0);
}

inline void enable_int1(Sense s) {
  HAL_EXTINT_MASK &= uint8_t(~_BV(INT1));
  HAL_EXTINT_SENSE = uint8_t((HAL_EXTINT_SENSE & ~(_BV(ISC11) | _BV(ISC10))) | (uint8_t(s) << ISC10));
  HAL_EXTINT_FLAGS = _BV(INTF1);
  HAL_EXTINT_MASK |= _BV(INT1);
}

inline void disable_int0() {
  HAL_EXTINT_MASK &= uint8_t(~_BV(INT0));
  HAL_EXTINT_FLAGS = _BV(INTF0);
}

inline void disable_int1() {
  HAL_EXTINT_MASK &= uint8_t(~_BV(INT1));
  HAL_EXTINT_FLAGS = _BV(INTF1);
}

constexpr uint8_t latch_flag(uint8_t line) { return line == 0 ? _BV(INTF0) : _BV(INTF1); }

inline void latch_edges(uint8_t line, bool rising) {
  const uint8_t shift = line == 0 ? ISC00 : ISC10;
  HAL_EXTINT_SENSE = uint8_t((HAL_EXTINT_SENSE & ~(3u << shift)) | ((rising ? 3u : 2u) << shift));
  HAL_EXTINT_FLAGS = latch_flag(line);
}

inline uint8_t latched() { return HAL_EXTINT_FLAGS; }
inline void clear_latched(uint8_t flags) { HAL_EXTINT_FLAGS = flags; }

}  // namespace ext_int
}  // namespace hal
