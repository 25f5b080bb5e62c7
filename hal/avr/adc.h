// The 10-bit successive-approximation ADC, used 8 bits at a time.
//
// Contract
//   init() selects AVCC as reference (REFS1:0 = 01), left-adjusts the result
//   (ADLAR = 1) so ADCH alone holds the top 8 bits, enables the ADC with the
//   given prescaler and, if asked, the conversion-complete interrupt
//   (ADC_vect). No conversion is started.
//   select(channel) picks a single-ended input 0..7; call it only while no
//   conversion runs (after ADC_vect, or before start()), so the new channel
//   applies to the next conversion as a whole.
//   start() begins one conversion: 13 ADC clocks, 25 for the first after
//   enabling (datasheet "Analog to Digital Converter", timing table).
//   read8() returns ADCH as an unsigned byte: 0..255 for 0..Vref, never a
//   signed type (a reading above 127 must not turn negative).
//   read10() returns the whole 10-bit result, 0..1023: ADCL is read first
//   (that locks ADCH until it is read: datasheet "ADCL and ADCH"), and the
//   left-adjusted pair is shifted down.
//
//   Register names and bits are the same on the ATmega16/32 and 328P.
#pragma once
#include <stdint.h>
#include "family.h"

namespace hal {
namespace adc {

// ADPS2:0 codes; the ADC clock is F_CPU / divisor.
enum class Prescaler : uint8_t { div2 = 1, div4 = 2, div8 = 3, div16 = 4, div32 = 5, div64 = 6, div128 = 7 };

constexpr uint8_t kMuxMask = 0x07;  // MUX2:0, single-ended inputs ADC0..ADC7

inline void init(Prescaler prescaler, bool interrupt) {
  ADMUX = _BV(REFS0) | _BV(ADLAR);  // AVCC reference, left adjusted, ADC0
  ADCSRA = uint8_t(_BV(ADEN) | (interrupt ? _BV(ADIF) | _BV(ADIE) : _BV(ADIF)) |
                   uint8_t(prescaler));  // ADIF written 1 = cleared
}

inline void select(uint8_t channel) { ADMUX = uint8_t((ADMUX & uint8_t(~kMuxMask)) | (channel & kMuxMask)); }
inline uint8_t channel() { return uint8_t(ADMUX & kMuxMask); }
// Read-modify-write of ADCSRA: a pending ADIF (write one to clear) would be
// cleared too; inside ADC_vect the hardware has already cleared it.
// Read-modify-write of ADCSRA: a pending ADIF (write one to clear) is
// cleared too; inside ADC_vect the hardware has already cleared it.
inline void start() { ADCSRA |= _BV(ADSC); }
inline bool busy() { return (ADCSRA & _BV(ADSC)) != 0; }
inline uint8_t read8() { return ADCH; }
inline uint16_t read10() { return uint16_t(ADCW >> 6); }  // ADCW: ADCL, then ADCH

}  // namespace adc
}  // namespace hal
