#include "clock.h"

#include <avr/interrupt.h>

// The clock above TCNT0: bits 8..31 of now(), counted by the overflow
// vector (least significant byte first). An assembler name, for the vector's
// assembly below.
volatile uint8_t clock_high[3] asm("clock_high");

#define CLOCK_STR2(x) #x
#define CLOCK_STR(x) CLOCK_STR2(x)
// The overflow vector's own section (-ffunction-sections names it after the
// vector). now() is placed there too: the vector table keeps that section in
// the image, so every image carries the reader with the vector even before
// its first caller (tests/sim/test_clock.cpp calls it on the chip), for
// about 40 bytes of flash.
#define CLOCK_SECTION ".text." CLOCK_STR(HAL_CLOCK_VECT)

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
__attribute__((section(CLOCK_SECTION))) uint32_t now() {
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

// The overflow vector: 256 ticks more. SEI is its first instruction, so a
// step match that comes while it runs waits only for its entry: 4 cycles of
// response, the JMP (3; an RJMP, 2, where the linker's relaxation reaches
// the handler from the table, as on the ATmega16), SEI (1) and the one
// instruction the AVR executes after SEI (2), then the step vector nests.
// The body touches one register and SREG. Cycles from the overflow when
// nothing carries: 4 + 3 + 22 = 29 including RETI (28 with an RJMP); every 256th overflow carries into the second byte (6 more),
// every 65536th into the third (4 more again).
ISR(HAL_CLOCK_VECT, ISR_NAKED) {
  asm volatile(
      "sei\n\t"                      // 1   8
      "push r24\n\t"                 // 2  10
      "in r24, __SREG__\n\t"         // 1
      "push r24\n\t"                 // 2
      "lds r24, clock_high\n\t"      // 2
      "inc r24\n\t"                  // 1  Z: it wrapped to 0, carry on
      "sts clock_high, r24\n\t"      // 2
      "brne 1f\n\t"                  // 2 taken, 1 not
      "lds r24, clock_high+1\n\t"    // 2
      "inc r24\n\t"                  // 1
      "sts clock_high+1, r24\n\t"    // 2
      "brne 1f\n\t"                  // 2 / 1
      "lds r24, clock_high+2\n\t"    // 2
      "inc r24\n\t"                  // 1
      "sts clock_high+2, r24\n\t"    // 2
      "1:\n\t"
      "pop r24\n\t"                  // 2
      "out __SREG__, r24\n\t"        // 1
      "pop r24\n\t"                  // 2
      "reti\n\t");                   // 4  29
}
