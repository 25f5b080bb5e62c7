// What the DC-servo leadscrew of firmware/boards/m16-servo.h claims
// (hal/avr/claims.h), in a header of its own so that tests/build/claims.cpp
// checks the board's own constants on the host.
//   Timer1: 10-bit fast PWM (mode 7, TOP 0x3FF, no prescaler: 15.625 kHz at
//   16 MHz) on OC1A (PD5), the L298's enable; its overflow interrupt is the
//   servo's time base (the PID's sample every 16th, the limit switch every
//   one). INT0: the motor encoder. INT1: the spindle's one channel.
// A part that also wants Timer1 (the step engine's or the stepper
// leadscrew's pace) or OC1A collides with it and the board does not compile.
#pragma once
#include "../../../hal/avr/claims.h"

namespace m16_servo_claims {

constexpr uint32_t kServo = hal::claim::timer1 | hal::claim::oc1a | hal::claim::int0;
constexpr uint32_t kSpindle = hal::claim::int1;

}  // namespace m16_servo_claims
