// Timer2 fast PWM on OC2 (PD7) of the ATmega16/32 (OC2A, the same pin, on
// the ATmega1284P), for a heater's MOSFET:
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

#if defined(__AVR_ATmega16__) || defined(__AVR_ATmega32__) || defined(__AVR_ATmega1284P__)
namespace hal {

namespace pwm_oc2_detail {
#if defined(TCCR2A)
// The ATmega1284P's Timer2 (OC2A on the same PD7): COM2A1:0 and WGM21:20 in
// TCCR2A, the clock select in TCCR2B (WGM22 = 0 there), the same CS codes.
inline void mode(uint8_t com) {
  TCCR2A = uint8_t(com | _BV(WGM21) | _BV(WGM20));
  TCCR2B = _BV(CS22) | _BV(CS20);
}
inline void duty(uint8_t value) { OCR2A = value; }
constexpr uint8_t kConnect = _BV(COM2A1);
#else
inline void mode(uint8_t com) { TCCR2 = uint8_t(com | _BV(WGM21) | _BV(WGM20) | _BV(CS22) | _BV(CS20)); }
inline void duty(uint8_t value) { OCR2 = value; }
constexpr uint8_t kConnect = _BV(COM21);
#endif
}  // namespace pwm_oc2_detail

struct PwmOc2 {
  using OutPin = Pin<'D', 7>;
  static constexpr uint32_t claims = claim::timer2 | claim::oc2a;
  static constexpr uint16_t prescaler = 128;
  static constexpr uint32_t frequency_hz() { return F_CPU / prescaler / 256; }

  static void init() {
    pwm_oc2_detail::duty(0);
    OutPin::low();
    OutPin::output();
    pwm_oc2_detail::mode(0);  // COM2x1:0 = 00: disconnected
  }
  static void set(uint8_t duty) {
    if (duty == 0) {
      pwm_oc2_detail::mode(0);  // PD7 is its PORT bit again: low
      return;
    }
    pwm_oc2_detail::duty(duty);
    pwm_oc2_detail::mode(pwm_oc2_detail::kConnect);
  }
};

}  // namespace hal
#endif
