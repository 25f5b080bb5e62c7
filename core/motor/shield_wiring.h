// Adafruit Motor Shield v1 wiring: which 74HC595 output drives each coil end
// of the two steppers (seed-000 section 1: MOTOR1_A = bit 2, MOTOR1_B = 3,
// MOTOR2_A = 1, MOTOR2_B = 4, MOTOR3_A = 5, MOTOR3_B = 7, MOTOR4_A = 0,
// MOTOR4_B = 6). Shared by the firmware's output driver and the simulator's
// decoder, so both read the same facts.
#pragma once
#include <stdint.h>

#include "phase_sequencer.h"

namespace am {

struct ShieldStepperWiring {
  uint8_t a_pos, b_pos, a_neg, b_neg;  // latch bits, coil-pattern order

  constexpr uint8_t mask() const { return uint8_t(a_pos | b_pos | a_neg | b_neg); }
  constexpr uint8_t latch_bits(uint8_t pattern) const {
    return uint8_t(((pattern & coil::a_pos) ? a_pos : 0) | ((pattern & coil::b_pos) ? b_pos : 0) |
                   ((pattern & coil::a_neg) ? a_neg : 0) | ((pattern & coil::b_neg) ? b_neg : 0));
  }
  constexpr uint8_t pattern(uint8_t latch) const {
    return uint8_t(((latch & a_pos) ? coil::a_pos : 0) | ((latch & b_pos) ? coil::b_pos : 0) |
                   ((latch & a_neg) ? coil::a_neg : 0) | ((latch & b_neg) ? coil::b_neg : 0));
  }
};

// Stepper 1 on M1/M2, stepper 2 on M3/M4.
constexpr ShieldStepperWiring shield_wiring(uint8_t stepper) {
  return stepper == 1 ? ShieldStepperWiring{0x04, 0x02, 0x08, 0x10}
                      : ShieldStepperWiring{0x20, 0x01, 0x80, 0x40};
}

// Index (0..7) of a pattern in the half-step cycle, or -1 if the pattern is no
// state of it (coils off, or an impossible combination).
inline int8_t half_step_index(uint8_t pattern) {
  for (uint8_t i = 0; i < 8; ++i) {
    if (half_step_pattern(i) == pattern) return int8_t(i);
  }
  return -1;
}

}  // namespace am
