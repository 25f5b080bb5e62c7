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

// Several pins of one port changed in a single write, so they switch in the
// same cycle (coil patterns), or read at one instant (endstops). A write is
// a read-modify-write of PORTx: atomic only with interrupts off or when no
// interrupt writes the same port.
template <char Port>
struct PortBits {
  static constexpr uint8_t pin_reg = family::pin_io_address(Port);
  static_assert(pin_reg != 0xFF, "this MCU has no such port");

  static void write(uint8_t mask, uint8_t bits) {
    _SFR_IO8(pin_reg + 2) = uint8_t((_SFR_IO8(pin_reg + 2) & uint8_t(~mask)) | (bits & mask));
  }
  static void output(uint8_t mask) { _SFR_IO8(pin_reg + 1) |= mask; }
  static void input(uint8_t mask) { _SFR_IO8(pin_reg + 1) &= uint8_t(~mask); }
  static uint8_t read() { return _SFR_IO8(pin_reg); }  // every pin's level, one IN
};

}  // namespace hal
