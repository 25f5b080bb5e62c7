// 8-bit fast PWM on an output compare channel of Timer0 or Timer2.
//
// Contract
//   Pwm8<Timer, Channel, Prescaler> (Timer 0 or 2, Channel 'A' or 'B',
//   Prescaler 1, 8 or 64; 1 by default) drives its OCnx pin in fast PWM mode 3
//   (TOP = 0xFF), non-inverting, the timer clocked at F_CPU / Prescaler:
//   F_CPU / 256 = 62.5 kHz at 16 MHz with no prescaler, above hearing, so a
//   microstepping winding does not whine; 7.8 kHz with prescaler 8 (the Uno's
//   Timer0, whose overflow is also the board's time base: firmware/engine/
//   clock.h). The prescaler is part of the claim (hal/avr/claims.h), so two
//   users of one timer that want different rates do not compile. init()
//   makes the pin an output and configures the timer through
//   pwm8_detail::start(), which a time base sharing the timer calls too
//   (idempotent: both channels of a timer and the time base set the same
//   mode and prescaler, in any order).
//   set(duty) writes OCRnx; the hardware buffers it until the next BOTTOM, so
//   a new duty starts with a whole period. duty 255 is a constant high
//   (datasheet: OCR = MAX), duty 0 still leaves a one-tick spike each period,
//   so a coil that must carry no current needs its bridge inputs low as well.
//
//   Registers are the ATmega328P's (datasheet ch. 14 and 17: TCCRnA holds
//   COMnA1:0 in bits 7:6, COMnB1:0 in 5:4, WGMn1:0 in 1:0; TCCRnB holds WGMn2
//   in bit 3 and CSn2:0 in 2:0; the CS codes differ: Timer0 1/8/64 = 1/2/3,
//   Timer2 1/8/64 = 1/2/4). The ATmega16/32 have one compare channel per
//   8-bit timer in a single TCCR0/TCCR2, so this header is not mapped there.
#pragma once
#include <stdint.h>

#include "claims.h"
#include "gpio.h"

#if defined(__AVR_ATmega328P__)
namespace hal {

namespace pwm8_detail {
template <bool A, typename X, typename Y>
struct Select {
  using type = X;
};
template <typename X, typename Y>
struct Select<false, X, Y> {
  using type = Y;
};

// Data-space addresses (datasheet register summary).
template <uint8_t Timer>
struct Timer8;
template <>
struct Timer8<0> {
  static constexpr uint16_t tccra = 0x44, tccrb = 0x45, ocra = 0x47, ocrb = 0x48;
  template <bool A> using Out = typename Select<A, Pin<'D', 6>, Pin<'D', 5>>::type;  // OC0A, OC0B
  static constexpr uint8_t cs(uint16_t prescaler) {
    return prescaler == 1 ? 1 : prescaler == 8 ? 2 : prescaler == 64 ? 3 : 0;
  }
};
template <>
struct Timer8<2> {
  static constexpr uint16_t tccra = 0xB0, tccrb = 0xB1, ocra = 0xB3, ocrb = 0xB4;
  template <bool A> using Out = typename Select<A, Pin<'B', 3>, Pin<'D', 3>>::type;  // OC2A, OC2B
  static constexpr uint8_t cs(uint16_t prescaler) {
    return prescaler == 1 ? 1 : prescaler == 8 ? 2 : prescaler == 64 ? 4 : 0;
  }
};

// The timer's part of the set-up, shared by its PWM channels and a time base
// counting its period: fast PWM mode 3 (WGM2:0 = 011) at the prescaler. The
// COM bits already set (other channels' pins) stay; `com` adds a channel's.
template <uint8_t Timer, uint16_t Prescaler>
inline void start(uint8_t com = 0) {
  using T = Timer8<Timer>;
  static_assert(T::cs(Prescaler) != 0, "8-bit PWM prescaler: 1, 8 or 64");
  _SFR_MEM8(T::tccra) = uint8_t((_SFR_MEM8(T::tccra) & 0xFC) | com | 0x03);  // WGM1:0 = 11
  _SFR_MEM8(T::tccrb) = T::cs(Prescaler);                                    // WGM2 = 0 (mode 3)
}
}  // namespace pwm8_detail

template <uint8_t Timer, char Channel, uint16_t Prescaler = 1>
struct Pwm8 {
  static_assert(Channel == 'A' || Channel == 'B', "channel A or B");
  using T = pwm8_detail::Timer8<Timer>;
  using OutPin = typename pwm8_detail::Timer8<Timer>::template Out<Channel == 'A'>;
  static constexpr uint16_t ocr = Channel == 'A' ? T::ocra : T::ocrb;
  // COMnx1:0 = 10, non-inverting: set at BOTTOM, clear on compare match.
  static constexpr uint8_t com = Channel == 'A' ? 0x80 : 0x20;
  static_assert(claim::rate(Timer, Prescaler) != 0, "8-bit PWM prescaler: 1, 8 or 64");
  // The timer's shared 8-bit PWM set-up at its rate, and this channel's pin.
  static constexpr uint32_t claims = (Timer == 0 ? claim::timer0_pwm8 : claim::timer2_pwm8) |
                                     claim::rate(Timer, Prescaler) |
                                     (Timer == 0 ? (Channel == 'A' ? claim::oc0a : claim::oc0b)
                                                 : (Channel == 'A' ? claim::oc2a : claim::oc2b));

  static void init() {
    set(0);
    OutPin::output();
    pwm8_detail::start<Timer, Prescaler>(com);
  }
  static void set(uint8_t duty) { _SFR_MEM8(ocr) = duty; }
  static constexpr uint32_t frequency_hz() { return F_CPU / Prescaler / 256; }
};

}  // namespace hal
#endif
