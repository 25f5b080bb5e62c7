// The ATmega32 board's printer hardware (seed-002) as a program sees it:
// the hot end, the endstops with homing, and the claims of all that. The
// printer programs (m32_printer.h) and the ATmega1284P's image
// (firmware/boards/m1284.h) build on it. Wiring: m32_wiring.h. Its
// declarations go straight into namespace board (a board's own names win
// over firmware/board.h's defaults only there).
#pragma once
#include "../../../hal/avr/pwm_oc2.h"
#include "m32_wiring.h"

namespace board {

using namespace m32_wiring;

// The hot end (docs/heater.md): NTC divider on ADC2 (PA2), MOSFET on OC2
// (PD7, Timer2's PWM at 488 Hz, disconnected for duty 0), TEMP_OK on PD6.
struct Heater {
  using Pwm = hal::PwmOc2;
  using TempOk = Pin<'D', 6>;
  static constexpr uint8_t adc_channel = 2;
  static constexpr uint32_t claims = Pwm::claims | hal::claim::adc;
};

// Hard limits, homing (G28) and soft limits on the min endstops
// (docs/homing.md, m32_wiring.h).
using Endstops = m32_wiring::EndstopsOn<Axes>;
constexpr bool kHoming = true;
constexpr HomingSettings<3> kHomingSettings = m32_wiring::printer_homing<Axes>();

using Claims = hal::ClaimSet<kStepClock, kClock, hal::claim::uart, Axes::Claims::all, Heater::claims, Endstops::claims>;

}  // namespace board
