// The watchdog as the soft-reset switch.
//
// Contract
//   reset() restarts the chip 15 ms later (16 ms nominal, the watchdog's own
//   oscillator) with interrupts off meanwhile: nothing the firmware runs
//   happens after the call. after_reset(), first thing in main(), stops a
//   watchdog a reset() left running (on the ATmega328P it stays on through
//   the reset it caused and would reset the chip again) and says whether it
//   caused this start.
#pragma once
#include <avr/interrupt.h>
#include <avr/wdt.h>

#include "family.h"

namespace hal {
namespace watchdog {

inline bool after_reset() {
  const bool by_watchdog = HAL_RESET_FLAGS & _BV(WDRF);
  HAL_RESET_FLAGS = 0;  // WDRF overrides WDE until cleared
  wdt_disable();
  return by_watchdog;
}

[[noreturn]] inline void reset() {
  cli();
  wdt_enable(WDTO_15MS);
  for (;;) {
  }
}

}  // namespace watchdog
}  // namespace hal
