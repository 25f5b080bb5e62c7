// The time base: a free-running 32-bit tick count for the main loop (dwell,
// timeouts, a heater's sample period, keypad debounce).
//
// Contract
//   init() starts it (before sei(); main() calls it once). now() is the
//   count in ticks: it starts near 0 at power-up, never goes backwards and
//   wraps at 2^32. One tick is board::kClock's prescaler over F_CPU
//   (hal/avr/claims.h, the board header says which timer and why):
//
//   | image    | timer                          | tick   | ticks_per_ms | wraps after |
//   |----------|--------------------------------|--------|--------------|-------------|
//   | uno      | Timer0 / 8, shared with Y's PWM | 0.5 us | 2000         | 35.8 min    |
//   | m32, m16 | Timer0 / 64, its own           | 4 us   | 250          | 4.8 h       |
//   | m16-8mhz | Timer0 / 64, its own           | 8 us   | 125          | 9.5 h       |
//
//   Compare times only through differences (reached(), due()): they are
//   right across the wrap for intervals up to 2^31 ticks (17.9 min on the
//   Uno). now() is for the main loop: it may run with interrupts on or off,
//   but not inside an interrupt handler (one that nests in the overflow
//   vector would see the count before the vector has extended it).
//   due(deadline, period) is the main loop's scheduler: true once the
//   deadline has come, which it then moves on by exactly one period, so a
//   periodic job never drifts; a loop that was late by k periods gets the k
//   missed beats on its next k calls (catching up), a job that would rather
//   skip them sets `deadline = clock::now() + period` itself. Start with
//   `deadline = clock::now()` (due at once) or `clock::now() + period`.
//
// Why it is built this way
//   The step interrupt must not notice the clock. The hardware counts the
//   low byte, so the only interrupt is the overflow, once per 256 ticks
//   (every 2048 cycles on the Uno, 16384 on the ATmega16/32), and its vector
//   enables interrupts with its first instruction (a naked vector, 29 cycles
//   response to RETI, in clock.cpp): a step match waits at most for that
//   vector's entry, never for its body. now() takes no lock at all: it reads
//   the software part, TCNT0 and the overflow flag, and reads again if the
//   vector ran meanwhile (the rationale is in clock.cpp), so the main loop's
//   reads never hold the step interrupt off either. (Do not include
//   <time.h> beside this header: avr-libc declares a ::clock() there.)
#pragma once
#include <stdint.h>

#include "../../hal/avr/clock_timer.h"
#include "../board.h"

namespace clock {

using Timer = hal::ClockTimer<board::kClock>;

constexpr uint32_t kTickHz = Timer::tick_hz;  // ticks per second
static_assert(kTickHz % 1000 == 0, "a whole number of ticks per millisecond");
constexpr uint32_t ticks_per_ms = kTickHz / 1000;
// Milliseconds in ticks (up to 2^32 / ticks_per_ms ms).
constexpr uint32_t ms(uint32_t n) { return n * ticks_per_ms; }

void init();
uint32_t now();

// Whether `deadline` has come (it is now or past, by less than 2^31 ticks).
inline bool reached(uint32_t deadline) { return int32_t(now() - deadline) >= 0; }

// True once per period: when `deadline` has come, which then moves on by
// `period` (see above).
inline bool due(uint32_t& deadline, uint32_t period) {
  if (!reached(deadline)) return false;
  deadline += period;
  return true;
}

}  // namespace clock
