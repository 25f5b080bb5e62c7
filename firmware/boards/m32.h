// Board: ATmega32 printer/CNC controller (seed-002).
// avrmotion-board: mcu=atmega32 f_cpu=16000000 app=cnc
//
// X Y Z E on step/dir drivers: steps PC0/PC2/PC4/PC6, directions
// PC1/PC3/PC5/PC7, enables PB0..PB3 (active low). Endstops (switch to ground,
// pulled up): X/Y/Z min on PD2/PD3/PD4, max on PA5/PA6/PA7. Thermistor on
// ADC2 (PA2), heater MOSFET on OC2 (PD7), TEMP_OK output on PD6 (the heater
// service: board::Heater below). One step is one
// basic length unit of 1 um (the seed's BLU_PER_MM = 1000). The seed's four
// axes only: the RAM (2 KB) goes to the look-ahead ring and, next, the heater.
#pragma once
#include "../../hal/avr/claims.h"
#include "../../hal/avr/gpio.h"
#include "../../hal/avr/pwm_oc2.h"
#include "../axes/axis_set.h"
#include "../axes/step_dir_axis.h"

namespace board {

using hal::Pin;
using Axes = AxisSet<StepDirAxis<'X', Pin<'C', 0>, Pin<'C', 1>, Pin<'B', 0>, true, 1000000>,
                     StepDirAxis<'Y', Pin<'C', 2>, Pin<'C', 3>, Pin<'B', 1>, true, 1000000>,
                     StepDirAxis<'Z', Pin<'C', 4>, Pin<'C', 5>, Pin<'B', 2>, true, 1000000>,
                     StepDirAxis<'E', Pin<'C', 6>, Pin<'C', 7>, Pin<'B', 3>, true, 1000000>>;

// Hardware claims (hal/avr/claims.h, checked when the image compiles): Timer1
// is the step clock, the UART talks to the host, Timer0 is the time base
// (firmware/engine/clock.h): its own, in normal mode with prescaler 64, one
// tick per 4 us, an overflow interrupt every 16384 cycles (29 of them, 0.2 %
// of the CPU); OC0 (PB3, axis E's enable) stays a port pin. The heater
// (below) takes Timer2 with OC2 (PD7) and the ADC.
constexpr uint32_t kStepClock = hal::claim::timer1;
constexpr uint32_t kClock = hal::claim::timer0_ovf | hal::claim::timer0 | hal::claim::timer0_div64;

// The hot end (docs/heater.md): NTC divider on ADC2 (PA2), MOSFET on OC2
// (PD7, Timer2's PWM at 488 Hz, disconnected for duty 0), TEMP_OK on PD6.
// kHeater makes the cnc program link the heater service (firmware/services/,
// firmware/apps/cnc/app.cmake) and take the heater M-codes.
constexpr bool kHeater = true;
struct Heater {
  using Pwm = hal::PwmOc2;
  using TempOk = Pin<'D', 6>;
  static constexpr uint8_t adc_channel = 2;
  static constexpr uint32_t claims = Pwm::claims | hal::claim::adc;
};

using Claims = hal::ClaimSet<kStepClock, kClock, hal::claim::uart, Axes::Claims::all, Heater::claims>;

constexpr uint32_t kBaud = 115200;
constexpr uint32_t kStepTimerHz = F_CPU;
constexpr uint32_t kMaxStepRate = 40000;
constexpr bool kGcode = true;  // the cnc program speaks G-code (docs/gcode.md)
constexpr uint8_t kPathBlocks = 5;  // look-ahead ring of G-code blocks (firmware/engine/path.h); RAM: the heater takes a block's, the stack needs 350 B
constexpr uint32_t kDefaultRate = 4000;    // steps/s (4 mm/s)
constexpr uint32_t kDefaultAccel = 500000;  // steps/s^2 (500 mm/s^2)
// Fastest ramp the planner keeps ahead of, with any axis at 40 kHz
// (tests/sim/test_invariants.cpp; docs/step-engine.md).
constexpr uint32_t kMaxAccel = 800000;  // steps/s^2
constexpr uint8_t kStepPulsePadCycles = 24;  // >= 1.9 us with the bookkeeping (DRV8825)
constexpr uint8_t kTimerPulseCycles = 0;  // no timer-pulsed axis

// First thing main() runs: the heater's MOSFET gate is driven low before
// anything else (until then the pin floats; the board's gate pull-down holds
// it off).
inline void init() {
  Pin<'D', 7>::low();  // heater off before the pin becomes an output
  Pin<'D', 7>::output();
  Pin<'D', 6>::low();  // TEMP_OK low: not at temperature
  Pin<'D', 6>::output();
  Pin<'D', 2>::input_pullup();
  Pin<'D', 3>::input_pullup();
  Pin<'D', 4>::input_pullup();
  Pin<'A', 5>::input_pullup();
  Pin<'A', 6>::input_pullup();
  Pin<'A', 7>::input_pullup();
  Axes::init();
}

}  // namespace board
