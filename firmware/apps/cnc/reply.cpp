// The answers in the board's style (reply.h). Out of line: every refusal
// site calls one function instead of repeating its framing.
#include "reply.h"

namespace reply {

const char kPositionRange[] PROGMEM = "move would leave the position range";
const char kTimerAxisAlone[] PROGMEM = "the hardware-timed axis moves alone";

void ok() { hal::uart::write_P(PSTR("ok\n")); }

void info_begin() { hal::uart::write_P(kMarlin ? PSTR("echo:") : PSTR("[MSG:")); }

void info_end() {
  if (!kMarlin) hal::uart::write(']');
  hal::uart::write('\n');
}

void info_P(const char* progmem_text) {
  info_begin();
  hal::uart::write_P(progmem_text);
  info_end();
}

void error_begin() { hal::uart::write_P(kMarlin ? PSTR("Error:") : PSTR("[MSG:")); }

void error_end(uint8_t grbl_code) {
  if (kMarlin) {
    hal::uart::write('\n');
    ok();
    return;
  }
  hal::uart::write_P(PSTR("]\nerror:"));
  hal::uart::write_u32(grbl_code);
  hal::uart::write('\n');
}

void error(uint8_t grbl_code, const char* progmem_reason) {
  error_begin();
  hal::uart::write_P(progmem_reason);
  error_end(grbl_code);
}

void unknown_command(const char* line) {
  hal::uart::write_P(PSTR("echo:Unknown command: \""));
  hal::uart::write(line);
  hal::uart::write_P(PSTR("\"\n"));
  ok();
}

}  // namespace reply
