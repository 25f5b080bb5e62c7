// The answers every line of the cnc protocol ends with: `ok`, or
// `error: <reason>` (docs/protocol.md, docs/gcode.md), and the banner the
// firmware greets the host with; the lathe's front end answers the same way.
#pragma once
#include <avr/pgmspace.h>

#include "../../../hal/avr/uart.h"

namespace reply {

inline void ok() { hal::uart::write_P(PSTR("ok\n")); }

inline void banner() {
  hal::uart::write_P(PSTR("avrmotion " AVRMOTION_VERSION " board="));
  hal::uart::write_P(PSTR(AVRMOTION_BOARD_NAME " mcu=" AVRMOTION_MCU_NAME));
  hal::uart::write_P(PSTR(" f_cpu="));
  hal::uart::write_u32(F_CPU);
  hal::uart::write('\n');
}

inline void error(const char* progmem_reason) {
  hal::uart::write_P(PSTR("error: "));
  hal::uart::write_P(progmem_reason);
  hal::uart::write('\n');
}

// A position in steps, or for an axis counted in fractions of a full step,
// in full steps with the decimals needed (1/64 -> 0.015625): "450", "-3.25".
inline void position(int32_t units, uint8_t per_full_step) {
  if (per_full_step == 1) {
    hal::uart::write_i32(units);
    return;
  }
  if (units < 0) hal::uart::write('-');
  const uint32_t magnitude = units < 0 ? uint32_t(-(units + 1)) + 1u : uint32_t(units);
  hal::uart::write_u32(magnitude / per_full_step);
  uint32_t millionths = (magnitude % per_full_step) * 1000000ul / per_full_step;
  if (millionths == 0) return;
  hal::uart::write('.');
  for (uint32_t digit = 100000; millionths != 0; digit /= 10) {
    hal::uart::write(uint8_t('0' + millionths / digit));
    millionths %= digit;
  }
}

}  // namespace reply
