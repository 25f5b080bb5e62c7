// Timer0 as a free-running time base: the 8-bit count (TCNT0) is the low
// byte of the clock, its overflow interrupt extends it in software
// (firmware/engine/clock_vector.S defines the vector, hal/avr/clock_vector.h
// names it).
//
// Contract
//   ClockTimer<Claim> takes the board's clock claim (hal/avr/claims.h):
//   `timer0_ovf`, one prescaler (`timer0_div8` or `timer0_div64`; div1 would
//   overflow every 256 cycles), and the timer's mode:
//   - `timer0`: the timer is the clock's own. init() runs it in normal mode
//     (WGM 0, counts 0..0xFF, OC0 pins disconnected) at the prescaler;
//   - `timer0_pwm8` (ATmega328P): the timer also drives 8-bit fast PWM at
//     that prescaler (hal/avr/pwm8.h). Mode 3 counts 0..0xFF as well, so its
//     overflow comes once per PWM period; init() sets the same mode and
//     prescaler the PWM channels set (hal::pwm8_detail::start, idempotent,
//     their COM bits kept), in whatever order the two are initialised.
//   init() clears a stale overflow flag and enables the overflow interrupt;
//   it never writes TCNT0 (a running PWM keeps its phase). The count starts
//   wherever the timer is.
//   count() reads TCNT0, overflow_pending() TOV0: set by the wrap from 0xFF
//   to 0, cleared by the hardware when the vector is entered.
//
//   Registers: the ATmega328P and ATmega1284P keep Timer0 in TCCR0A/TCCR0B,
//   its flags in TIFR0 and its mask in TIMSK0 (datasheet ch. 14); the
//   ATmega16/32 in one
//   TCCR0 (FOC0, WGM00, COM01:0, WGM01, CS02:0), TIFR and TIMSK, shared with
//   Timer1 and Timer2 (datasheets "8-bit Timer/Counter0"). CS codes are the
//   same on both: 8 = 010, 64 = 011. The vector is TIMER0_OVF_vect on both.
#pragma once
#include <stdint.h>

#include "claims.h"
#include "clock_vector.h"
#include "family.h"
#if defined(__AVR_ATmega328P__)
#include "pwm8.h"
#endif


namespace hal {

template <uint32_t Claim>
struct ClockTimer {
  static_assert(Claim & claim::timer0_ovf, "the time base runs on Timer0's overflow: claim::timer0_ovf");
  static constexpr uint16_t prescaler = claim::prescaler_of(Claim, 0);
  static_assert(prescaler == 8 || prescaler == 64, "the time base's prescaler: claim::timer0_div8 or timer0_div64");
  static constexpr bool shares_pwm8 = (Claim & claim::timer0_pwm8) != 0;
  static_assert(shares_pwm8 != ((Claim & claim::timer0) != 0),
                "the time base owns Timer0 (claim::timer0) or counts its 8-bit PWM (claim::timer0_pwm8)");
  static constexpr uint32_t tick_hz = F_CPU / prescaler;
  static constexpr uint8_t cs = prescaler == 8 ? 0x02 : 0x03;  // CS02:0

#if defined(__AVR_ATmega328P__) || defined(__AVR_ATmega1284P__)
#if defined(__AVR_ATmega328P__)
  static void start_shared_pwm8() { pwm8_detail::start<0, prescaler>(); }
#else
  static_assert(!shares_pwm8, "no 8-bit PWM HAL on the ATmega1284P: the time base owns Timer0 there");
  static void start_shared_pwm8() {}
#endif
  static void init() {
    if (shares_pwm8) {
      start_shared_pwm8();
    } else {
      TCCR0A = 0;  // normal mode, OC0A/OC0B disconnected
      TCCR0B = cs;
    }
    TIFR0 = _BV(TOV0);  // write one to clear
    TIMSK0 |= _BV(TOIE0);
  }
  static uint8_t count() { return TCNT0; }
  static bool overflow_pending() { return (TIFR0 & _BV(TOV0)) != 0; }
#elif defined(__AVR_ATmega16__) || defined(__AVR_ATmega32__)
  static_assert(!shares_pwm8, "no 8-bit PWM HAL on the ATmega16/32: the time base owns Timer0 there");
  static void init() {
    TCCR0 = cs;          // normal mode, OC0 disconnected
    TIFR = _BV(TOV0);    // write one to clear (the other flags: writing 0 does nothing)
    TIMSK |= _BV(TOIE0);  // beside Timer1's OCIE1A
  }
  static uint8_t count() { return TCNT0; }
  static bool overflow_pending() { return (TIFR & _BV(TOV0)) != 0; }
#else
#error "avrmotion: no clock timer map for this MCU"
#endif
};

}  // namespace hal
