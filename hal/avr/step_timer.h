// Timer1 as the step clock: CTC mode (TOP = OCR1A), no prescaler, so one tick
// is one CPU cycle and a period of N ticks is exactly N cycles. The compare-A
// interrupt (TIMER1_COMPA_vect) is the step interrupt; the firmware defines it.
//
// In CTC mode OCR1A is not double-buffered: a value written inside the
// interrupt takes effect for the period that has just begun, which is what the
// step engine relies on. Writes must land before the counter passes them, so
// the shortest period is bounded by the interrupt's own length (the engine
// clamps rates accordingly).
#pragma once
#include <stdint.h>
#include "family.h"

namespace hal {
namespace step_timer {

constexpr uint8_t kOc1aSet = _BV(COM1A1) | _BV(COM1A0);
constexpr uint8_t kOc1aClear = _BV(COM1A1);

inline void init() {
  TCCR1A = kOc1aClear;         // OC1A low until armed; WGM11:10 = 0
  TCCR1B = _BV(WGM12);         // CTC, clock stopped
  HAL_TIMER1_MASK |= _BV(OCIE1A);
}

// Starts counting from zero; the first compare interrupt follows after
// compare + 1 cycles.
inline void start(uint16_t compare) {
  TCNT1 = 0;
  OCR1A = compare;
  HAL_TIMER1_FLAGS = _BV(OCF1A);  // drop a match left from before the stop
  TCCR1B = _BV(WGM12) | _BV(CS10);
}

// Stops the clock and drops a match that raised the flag meanwhile: left
// pending, it would enter the step vector once more with nothing to step.
inline void stop() {
  TCCR1B = _BV(WGM12);
  HAL_TIMER1_FLAGS = _BV(OCF1A);
}

// Stops the clock at once and forces OC1A low (a soft reset: no further
// edge, timed or hardware-made, after this).
inline void halt() {
  TCCR1B = _BV(WGM12);
  TCCR1A = kOc1aClear;
  HAL_FORCE_OC1A_REG = HAL_FORCE_OC1A_VALUE;
}

inline void set_compare(uint16_t compare) { OCR1A = compare; }

// The same CTC clock at F_CPU / 8 (one tick per 8 cycles: periods up to
// 524280 cycles, 30.5 Hz at 16 MHz), for a pace slower than the step engine's
// (the lathe's leadscrew moves).
inline void start_div8(uint16_t compare) {
  TCNT1 = 0;
  OCR1A = compare;
  HAL_TIMER1_FLAGS = _BV(OCF1A);
  TCCR1B = _BV(WGM12) | _BV(CS11);
}

// Hardware step pulses on OC1A. The rising edge is made by the compare match
// itself, so it lands on the exact timer tick whatever the interrupt latency;
// the interrupt only ends the pulse (FOC with "clear" forces the pin low
// without a match) and arms the next one ("set on match"). WGM11:10 are 0 in
// CTC mode, so TCCR1A holds nothing but these bits.
inline void arm_pulse() { TCCR1A = kOc1aSet; }
// Ending a pulse is the step vector's own job (firmware/engine/step_vector.S:
// "clear" mode, then HAL_FORCE_OC1A_REG = HAL_FORCE_OC1A_VALUE).
// Leaves OC1A driven low by "clear on match" (a match then changes nothing).
inline void disarm_pulse() { TCCR1A = kOc1aClear; }

}  // namespace step_timer
}  // namespace hal
