// 74HC595 shift-register writer by direct port access.
//
// Shifts a byte MSB first (bit 7 reaches output Q7), then pulses the storage
// latch, the order the Adafruit Motor Shield v1 expects. Fully unrolled: about
// five cycles a bit, no calls, so the step interrupt can afford one write per
// step.
#pragma once
#include <stdint.h>

namespace hal {

template <typename LatchPin, typename ClockPin, typename DataPin, typename EnablePin>
struct Latch595 {
  using Storage = LatchPin;
  using Clock = ClockPin;
  using Data = DataPin;
  using Enable = EnablePin;

  // Outputs low, storage cleared to zero, then outputs enabled (EN active
  // low): the coils are never energised by power-on garbage in the register.
  static void init() {
    LatchPin::output();
    ClockPin::output();
    DataPin::output();
    EnablePin::high();
    EnablePin::output();
    write(0);
    EnablePin::low();
  }

  static void write(uint8_t value) {
    LatchPin::low();
    shift_bit<7>(value);
    shift_bit<6>(value);
    shift_bit<5>(value);
    shift_bit<4>(value);
    shift_bit<3>(value);
    shift_bit<2>(value);
    shift_bit<1>(value);
    shift_bit<0>(value);
    LatchPin::high();
  }

 private:
  template <uint8_t Bit>
  static void shift_bit(uint8_t value) {
    ClockPin::low();
    if (value & (1u << Bit)) DataPin::high();
    else DataPin::low();
    ClockPin::high();
  }
};

}  // namespace hal
