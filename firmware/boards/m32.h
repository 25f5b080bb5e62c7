// Board: ATmega32 printer/CNC controller (seed-002), as the printer: the hot
// end and the G-code machine. Wiring: firmware/boards/common/m32_wiring.h.
// avrmotion-board: mcu=atmega32 f_cpu=16000000 app=cnc
#pragma once
#include "../../hal/avr/pwm_oc2.h"
#include "common/m32_wiring.h"

namespace board {

using namespace m32_wiring;

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

// Hard limits, homing (G28) and soft limits on the min endstops
// (docs/homing.md, m32_wiring.h).
using Endstops = EndstopWiring;
constexpr bool kHoming = true;
constexpr HomingSettings<3> kHomingSettings = kPrinterHoming;

using Claims = hal::ClaimSet<kStepClock, kClock, hal::claim::uart, Axes::Claims::all, Heater::claims, Endstops::claims>;

constexpr bool kGcode = true;  // the cnc program speaks G-code (docs/gcode.md)
constexpr Protocol kProtocol = Protocol::marlin;  // printer hosts: printcore, OctoPrint (docs/protocol.md)
// A printer host sends G-code only: the flash of the direct controls (MOVE,
// POS, WAIT, RELEASE, MODE) holds Marlin's protocol instead; the m32-cnc
// image of this board keeps them.
constexpr bool kCommands = false;
// The flash the heater needs: G2/G3 (7.5 KB) and the odometer (1 KB) are
// in the m32-cnc image of this board instead; M114 counts where the queued
// motion ends.
constexpr bool kArcs = false;
constexpr bool kOdometer = false;
constexpr uint8_t kPathBlocks = 5;  // look-ahead ring of G-code blocks (firmware/engine/path.h); RAM: the heater takes a block's, the stack needs 350 B

}  // namespace board
