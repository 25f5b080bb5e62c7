// Board: Arduino Uno + Adafruit Motor Shield v1 (seed-000 section 1).
// avrmotion-board: mcu=atmega328p f_cpu=16000000 app=cnc
//
// Two bipolar steppers through the shield's 74HC595 (D12 latch, D4 clock,
// D7 output enable active low, D8 data) and two L293D whose enables are D11/D3
// (stepper 1, axis X) and D5/D6 (stepper 2, axis Y). Travel is counted for a
// 200-step motor on an 8 mm-lead screw: 25 full steps per mm. (A ULN2003
// axis, as on the m16, would cost 1 KB of flash this image needs for the
// grbl protocol.) Axis Z is an external step/dir driver on the shield's servo header: STEP on
// D9 (OC1A, timed by the step timer's hardware), DIR on D10, ENABLE on A4
// (active low); 400 steps per mm (16 microsteps, 8 mm lead).
#pragma once
#include "../../hal/avr/claims.h"
#include "../../hal/avr/gpio.h"
#include "../../hal/avr/latch595.h"
#include "../../hal/avr/pwm8.h"
#include "../axes/axis_set.h"
#include "../axes/shield_stepper.h"
#include "../axes/timer_step_axis.h"

namespace board {

using hal::Pin;
using Latch = hal::Latch595<Pin<'B', 4>, Pin<'D', 4>, Pin<'B', 0>, Pin<'D', 7>>;
// Enables by 8-bit fast PWM: stepper 1 M1 = D11 (OC2A), M2 = D3 (OC2B) on
// Timer2 with no prescaler, 62.5 kHz; stepper 2 M3 = D6 (OC0A), M4 = D5 (OC0B)
// on Timer0 with prescaler 8, 7.8 kHz, because Timer0's overflow is also the
// board's time base (kClock below).
constexpr uint16_t kTimer0Prescaler = 8;
using Axes = AxisSet<ShieldStepper<'X', 1, Latch, hal::Pwm8<2, 'A'>, hal::Pwm8<2, 'B'>, 25000>,
                     ShieldStepper<'Y', 2, Latch, hal::Pwm8<0, 'A', kTimer0Prescaler>,
                                   hal::Pwm8<0, 'B', kTimer0Prescaler>, 25000>,
                     TimerStepAxis<'Z', Pin<'B', 2>, Pin<'C', 4>, true, 400000>>;

// Hardware claims (hal/avr/claims.h, checked when the image compiles): Timer1
// is the step clock and its OC1A the Z axis's STEP; Timers 0 and 2 drive the
// shield's enable PWM (the axes claim them); the UART talks to the host.
// Every timer is taken, so the time base (firmware/engine/clock.h) shares
// Timer0 with stepper 2's PWM: it counts the PWM's period (mode 3, 0..0xFF)
// and its overflow extends the count, one tick per 8 cycles (0.5 us), an
// overflow interrupt every 2048 cycles (29 of them, 1.4 % of the CPU). The
// claim says "Timer0's overflow is the clock and its PWM runs at F_CPU / 8 /
// 256": a second time base, a PWM channel at another rate or a part that
// reprograms Timer0 do not compile. Prescaler 8 rather than 64: stepper 2's
// enables carry the microstep sine currents, and at 7.8 kHz (a 128 us
// period, well under a winding's L/R of about 1 ms) the current still
// averages the duty with little ripple, where 977 Hz (prescaler 64, the
// Arduino default AFMotor lived with) ripples by a large part of it and hums
// at the ear's most sensitive pitch; 7.8 kHz is audible too, 62.5 kHz was
// not. The price: 8 times as many overflow interrupts as prescaler 64 (1.4 %
// of the CPU instead of 0.2 %) and a clock that wraps after 35.8 min instead
// of 4.8 h. Timer2 keeps stepper 1 at 62.5 kHz.
constexpr uint32_t kStepClock = hal::claim::timer1;
constexpr uint32_t kClock =
    hal::claim::timer0_ovf | hal::claim::timer0_pwm8 | hal::claim::rate(0, kTimer0Prescaler);
using Claims = hal::ClaimSet<kStepClock, kClock, hal::claim::uart, Axes::Claims::all>;

constexpr uint32_t kBaud = 115200;
constexpr uint32_t kStepTimerHz = F_CPU;
constexpr uint32_t kMaxStepRate = 20000;
// No kRealtime: grbl's realtime bytes and feed hold (docs/realtime.md) need
// about 2.4 KB more flash than this image has left.
constexpr bool kGcode = true;  // the cnc program speaks G-code (docs/gcode.md)
constexpr bool kArcs = false;  // G2/G3 need about 4 KB of flash; this image has 1.1 KB left
constexpr uint8_t kPathBlocks = 5;  // look-ahead ring of G-code blocks (firmware/engine/path.h); RAM: the stack needs 360 B
constexpr uint32_t kDefaultRate = 400;   // steps/s
constexpr uint32_t kDefaultAccel = 800;  // steps/s^2
// Fastest ramp the exact trapezoid keeps ahead of with the Z axis at 160 kHz,
// where the step interrupt leaves the main loop a fifth of the CPU: 350000
// and 380000 were still exact, 400000 starved at the top of a 64000-step
// triangle (tests/sim/test_invariants.cpp, docs/step-engine.md).
constexpr uint32_t kMaxAccel = 300000;  // steps/s^2
constexpr uint8_t kStepPulsePadCycles = 0;  // coils, not pulses: no width to meet
constexpr uint8_t kTimerPulseCycles = 32;  // 2 us: A4988, DRV8825 (1.9 us) and TMC drivers

inline void init() {
  Latch::init();
  Axes::init();
}

}  // namespace board
