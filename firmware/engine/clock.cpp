#include "clock.h"

// The clock above TCNT0: bits 8..31 of now(), counted by the overflow
// vector (firmware/engine/clock_vector.S, least significant byte first).
// An assembler name, for that vector.
volatile uint8_t clock_high[3] asm("clock_high");

// now() is kept in every image with the vector, even before its first
// caller (tests/sim/test_clock.cpp calls it on the chip): the vector
// (clock_vector.S) refers to it, for about 40 bytes of flash.

namespace clock {

void init() { Timer::init(); }

// Lock-free: interrupts stay as the caller has them. The vector's work
// (the hardware clears TOV0 on entry, the body increments clock_high) is
// seen by this code as one step between two of its instructions, because
// the main loop runs only when no handler does. So:
//   - if the vector ran at any time between the first read of clock_high[0]
//     and the last, that byte differs (every increment changes it): read
//     again, at most once per overflow (every 2048 cycles or more);
//   - otherwise clock_high is whole and belongs to the period in which TCNT0
//     was read, unless the counter wrapped before TIFR was read and the
//     vector has not run yet (it is pending, or interrupts are off): then
//     TOV0 is set, the wrap lies before the TIFR read, so TCNT0 read once
//     more is in the new period, and the period count is one more than
//     clock_high says.
// The TCNT0 read before a wrap and TIFR after it is the race this resolves;
// no guess from TCNT0's value is needed (nothing holds the vector off for a
// whole period of 256 ticks).
uint32_t now() {
  union {
    uint32_t ticks;
    uint8_t byte[4];  // little-endian, as avr-gcc lays out a uint32_t
  } t;
  bool wrapped;
  do {
    t.byte[1] = clock_high[0];
    t.byte[2] = clock_high[1];
    t.byte[3] = clock_high[2];
    t.byte[0] = Timer::count();
    wrapped = Timer::overflow_pending();
    if (wrapped) t.byte[0] = Timer::count();
  } while (t.byte[1] != clock_high[0]);
  if (wrapped) t.ticks += 0x100;
  return t.ticks;
}

}  // namespace clock
