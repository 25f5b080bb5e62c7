// Timer2 fast PWM on OC2 (PD7) of the ATmega16/32, for a heater's MOSFET:
// duty 0 is no pulse at all.
//
// Contract
//   init() sets OCR2 to 0 and Timer2 to fast PWM (WGM21:0 = 11, TOP 0xFF) at
//   F_CPU / 128 (CS22:0 = 101): 488 Hz at 16 MHz, the seed printer's rate,
//   slow enough for a MOSFET driven from a port pin and fast against a hot
//   end's seconds of thermal lag. OC2 stays disconnected; PD7 is made a low
//   output (the board has already done so at reset).
//   set(duty): 0 disconnects OC2 (COM21:0 = 00) so PD7 is its PORT bit, low:
//   no current at all (fast PWM at OCR2 = 0 would still pulse one tick of
//   every period, datasheet "Fast PWM Mode"). 1..255 write OCR2 and connect
//   OC2 non-inverting (COM21:0 = 10): the pin is high for duty + 1 of every
//   256 ticks, 255 is a constant high. OCR2 is double-buffered at BOTTOM, so
//   a new duty starts with a whole period; a disconnect acts at once.
//   claims: Timer2 (its mode and clock) and its compare pin (hal/avr/claims.h).
#pragma once
#include <stdint.h>

#include "claims.h"
#include "gpio.h"

#if defined(__AVR_ATmega16__) || defined(__AVR_ATmega32__)
namespace hal {

struct PwmOc2 {
  using OutPin = Pin<'D', 7>;
  static constexpr uint32_t claims = claim::timer2 | claim::oc2a;
  static constexpr uint16_t prescaler = 128;
  static constexpr uint32_t frequency_hz() { return F_CPU / prescaler / 256; }
  static constexpr uint8_t kMode = _BV(WGM21) | _BV(WGM20) | _BV(CS22) | _BV(CS20);

  static void init() {
    OCR2 = 0;
    OutPin::low();
    OutPin::output();
    TCCR2 = kMode;  // COM21:0 = 00: disconnected
  }
  static void set(uint8_t duty) {
    if (duty == 0) {
      TCCR2 = kMode;  // PD7 is its PORT bit again: low
      return;
    }
    OCR2 = duty;
    TCCR2 = kMode | _BV(COM21);
  }
};

}  // namespace hal
#endif
