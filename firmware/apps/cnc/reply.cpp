// The answers in the board's style (reply.h). Out of line: every refusal
// site calls one function instead of repeating its framing.
#include "reply.h"

namespace reply {

bool marlin_now = kMarlin;

uint8_t refusal_code(planner::Refusal r) {
  return r == planner::Refusal::timer_axis_not_alone ? code::timer_axis_alone
         : r == planner::Refusal::alarm              ? code::alarm_lock
         : r == planner::Refusal::soft_limit         ? code::soft_limit
                                                     : code::invalid_target;
}

void ok() { hal::uart::write_P(PSTR("ok\n")); }

void info_begin() { hal::uart::write_P(marlin() ? PSTR("echo:") : PSTR("[MSG:")); }

void info_end() {
  if (!marlin()) hal::uart::write(']');
  hal::uart::write('\n');
}

void info_P(const char* progmem_text) {
  info_begin();
  hal::uart::write_P(progmem_text);
  info_end();
}

void error_begin() {
  // grbl: the reason as an info line, `[MSG:` (one copy of the text where
  // both styles are in the image; the others keep their own layout).
  if (board::kProtocolSwitch && !marlin()) return info_begin();
  hal::uart::write_P(marlin() ? PSTR("Error:") : PSTR("[MSG:"));
}

void error_end(uint8_t grbl_code) {
  if (marlin()) {
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

void alarm(uint8_t grbl_alarm, const char* progmem_reason) {
  if (marlin()) {
    error_begin();
    hal::uart::write_P(progmem_reason);
    hal::uart::write_P(PSTR(", M999 unlocks\n"));
    return;
  }
  hal::uart::write_P(PSTR("ALARM:"));
  hal::uart::write_u32(grbl_alarm);
  hal::uart::write('\n');
  info_P(progmem_reason);
  info_P(PSTR("'$X' to unlock"));
}

}  // namespace reply
