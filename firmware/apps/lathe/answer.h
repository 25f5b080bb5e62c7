// The lathe front end's answers (docs/lathe.md): `ok`, or `error: <reason>`,
// one per line, and the banner it greets the host with. Its own plain
// style: the lathe has no grbl or Marlin host (the cnc program's styles are
// firmware/apps/cnc/reply.h).
#pragma once
#include <avr/pgmspace.h>

#include "../../../hal/avr/uart.h"

namespace answer {

inline void ok() { hal::uart::write_P(PSTR("ok\n")); }

inline void banner() {
  hal::uart::write_P(PSTR("avrmotion " AVRMOTION_VERSION " board=" AVRMOTION_BOARD_NAME " mcu=" AVRMOTION_MCU_NAME
                          " f_cpu="));
  hal::uart::write_u32(F_CPU);
  hal::uart::write('\n');
}

inline void error(const char* progmem_reason) {
  hal::uart::write_P(PSTR("error: "));
  hal::uart::write_P(progmem_reason);
  hal::uart::write('\n');
}

}  // namespace answer
