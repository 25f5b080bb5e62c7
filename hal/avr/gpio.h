// Compile-time GPIO pins. Every access compiles to a single SBI/CBI/SBIS
// instruction because port and bit are template constants, which is what lets
// the step interrupt set step lines and shift the latch without library calls.
#pragma once
#include <stdint.h>
#include "family.h"

namespace hal {

template <char Port, uint8_t Bit>
struct Pin {
  static constexpr uint8_t pin_reg = family::pin_io_address(Port);
  static_assert(pin_reg != 0xFF, "this MCU has no such port");
  static_assert(Bit < 8, "bit out of range");
  static constexpr uint8_t mask = uint8_t(1u << Bit);
  static constexpr char port = Port;
  static constexpr uint8_t bit = Bit;

  static void high() { _SFR_IO8(pin_reg + 2) |= mask; }
  static void low() { _SFR_IO8(pin_reg + 2) &= uint8_t(~mask); }
  static void set(bool on) { if (on) high(); else low(); }
  static void output() { _SFR_IO8(pin_reg + 1) |= mask; }
  static void input_pullup() {
    _SFR_IO8(pin_reg + 1) &= uint8_t(~mask);
    high();
  }
  static bool read() { return (_SFR_IO8(pin_reg) & mask) != 0; }
};

}  // namespace hal
