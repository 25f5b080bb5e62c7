// The ATmega32 printer/CNC controller's wiring (seed-002), shared by the two
// programs it can run: firmware/boards/m32.h (the printer: hot end, G-code
// lines) and firmware/boards/m32-cnc.h (the mill: arcs, positions counted
// mid-move). 32 KB of flash hold one or the other set beside the G-code
// machine, not both.
//
// X Y Z E on step/dir drivers: steps PC0/PC2/PC4/PC6, directions
// PC1/PC3/PC5/PC7, enables PB0..PB3 (active low). Endstops (switch to ground,
// pulled up): X/Y/Z min on PD2/PD3/PD4, max on PA5/PA6/PA7. Thermistor on
// ADC2 (PA2), heater MOSFET on OC2 (PD7), TEMP_OK output on PD6. One step is
// one basic length unit of 1 um (the seed's BLU_PER_MM = 1000). The seed's
// four axes only: the RAM (2 KB) goes to the look-ahead ring and the heater.
#pragma once
#include "../../../hal/avr/claims.h"
#include "../../../hal/avr/gpio.h"
#include "../../axes/axis_set.h"
#include "../../axes/endstops.h"
#include "../../axes/step_dir_axis.h"

namespace m32_wiring {

using hal::Pin;
// The axes at XY, Z and E steps per metre (a printer profile's,
// firmware/boards/m32-i3.h); the seed's 1 um a step on all four.
template <uint32_t XY, uint32_t Z, uint32_t E>
using AxesAt = AxisSet<StepDirAxis<'X', Pin<'C', 0>, Pin<'C', 1>, Pin<'B', 0>, true, XY>,
                       StepDirAxis<'Y', Pin<'C', 2>, Pin<'C', 3>, Pin<'B', 1>, true, XY>,
                       StepDirAxis<'Z', Pin<'C', 4>, Pin<'C', 5>, Pin<'B', 2>, true, Z>,
                       StepDirAxis<'E', Pin<'C', 6>, Pin<'C', 7>, Pin<'B', 3>, true, E>>;
using Axes = AxesAt<1000000, 1000000, 1000000>;

// The min endstops of X, Y and Z (docs/homing.md): switches to ground on the
// pins' pull-ups, closed reads low. PD2 and PD3 are INT0's and INT1's pins,
// PD4 is OC1B's: reading a switch there claims them (a program that uses
// them, m32.h, adds EndstopWiring::claims to its set).
template <typename A>
using EndstopsOn = EndstopSet<A, false, Endstop<'X', Pin<'D', 2>, hal::claim::int0>,
                              Endstop<'Y', Pin<'D', 3>, hal::claim::int1>, Endstop<'Z', Pin<'D', 4>, hal::claim::oc1b>>;
using EndstopWiring = EndstopsOn<Axes>;
// Homing on them: X and Y home at 25 mm/s and locate at 1 mm/s, Z at 4 and
// 0.5 mm/s; 1 mm back-off and pull-off; after homing every axis is at 0 and
// may go 200 mm (Z 180 mm) up from there: an i3-style printer. In steps of
// the axes A (um / mm per step: steps per metre / 1000).
constexpr HomingAxis homing_axis(uint32_t spm, uint32_t seek_um_s, uint32_t locate_um_s, uint32_t travel_um) {
  return HomingAxis{uint16_t(seek_um_s * (spm / 1000) / 1000), uint16_t(locate_um_s * (spm / 1000) / 1000),
                    uint16_t(spm / 1000), uint16_t(spm / 1000), 0, travel_um / 1000 * (spm / 1000)};
}
template <typename A>
constexpr HomingSettings<3> printer_homing() {
  return {{homing_axis(A::steps_per_m_at(0), 25000, 1000, 200000),
           homing_axis(A::steps_per_m_at(1), 25000, 1000, 200000),
           homing_axis(A::steps_per_m_at(2), 4000, 500, 180000)}};
}

// Hardware claims (hal/avr/claims.h, checked when the image compiles): Timer1
// is the step clock, the UART talks to the host, Timer0 is the time base
// (firmware/engine/clock.h): its own, in normal mode with prescaler 64, one
// tick per 4 us, an overflow interrupt every 16384 cycles (29 of them, 0.2 %
// of the CPU); OC0 (PB3, axis E's enable) stays a port pin. The printer's
// heater takes Timer2 with OC2 (PD7) and the ADC.
constexpr uint32_t kStepClock = hal::claim::timer1;
constexpr uint32_t kClock = hal::claim::timer0_ovf | hal::claim::timer0 | hal::claim::timer0_div64;

constexpr uint32_t kBaud = 115200;
constexpr uint32_t kStepTimerHz = F_CPU;
constexpr uint32_t kMaxStepRate = 40000;
constexpr uint32_t kDefaultRate = 4000;    // steps/s (4 mm/s)
constexpr uint32_t kDefaultAccel = 500000;  // steps/s^2 (500 mm/s^2)
// Fastest ramp the planner keeps ahead of, with any axis at 40 kHz
// (tests/sim/test_invariants.cpp; docs/step-engine.md).
constexpr uint32_t kMaxAccel = 800000;  // steps/s^2
constexpr uint8_t kStepPulsePadCycles = 24;  // >= 1.9 us with the bookkeeping (DRV8825)
constexpr uint8_t kTimerPulseCycles = 0;  // no timer-pulsed axis

// First thing main() runs: the heater's MOSFET gate is driven low before
// anything else (until then the pin floats; the board's gate pull-down holds
// it off), on either program.
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
  EndstopWiring::init();
  Axes::init();
}

}  // namespace m32_wiring
