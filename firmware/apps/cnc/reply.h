// The answers every line of the cnc protocol ends with, in the board's style
// (board::kProtocol, docs/protocol.md; on a board with kProtocolSwitch the
// style in force, the setting $200: marlin()):
//   grbl    `ok`, or `[MSG:<reason>]` and `error:<n>` (grbl 1.1's number
//           where the refusal has a grbl meaning, ours from 100 up);
//   Marlin  `ok`, or `Error:<reason>` and `ok` (Marlin acknowledges every
//           line; the host's flow control waits for the `ok`).
// Info lines (warnings, reports) are `[MSG:...]` or `echo:...`: info_begin()
// and info_end() frame them. And the alarm line.
#pragma once
#include <avr/pgmspace.h>

#include "../../../hal/avr/uart.h"
#include "../../board.h"
#include "../../engine/planner.h"

namespace reply {

constexpr bool kMarlin = board::kProtocol == Protocol::marlin;
// The style in force: the constant, or where the board switches styles at
// run time (board::kProtocolSwitch) the flag the settings set at boot and
// at `$200=` (firmware/services/settings.cpp). Only that board links it.
extern bool marlin_now;
inline bool marlin() { return board::kProtocolSwitch ? marlin_now : kMarlin; }
inline void set_marlin(bool on) {
  if (board::kProtocolSwitch) marlin_now = on;
}

// grbl 1.1's error numbers (its interface document) for the refusals that
// have a grbl meaning, and avrmotion's own from 100 up for those that have
// none (docs/protocol.md lists every one).
namespace code {
constexpr uint8_t expected_letter = 1, bad_number = 2, bad_system_command = 3, line_overflow = 11,
                  unsupported = 20, modal_group = 21, undefined_feed = 22, axis_conflict = 24,
                  repeated_word = 25, no_axis_words = 26, bad_line_number = 27, value_missing = 28,
                  invalid_target = 33, arc_radius = 34, no_offsets = 35, unused_words = 36, alarm_lock = 9,
                  homing_off = 5, step_rate = 12;
// avrmotion's own
constexpr uint8_t out_of_range = 100, comment_open = 101, several_actions = 102, arc_mixed = 103,
                  bad_mode = 104, no_modes = 105, mode_unavailable = 106, heater = 107,
                  move_too_long = 108, timer_axis_alone = 109, zero_speed = 110, zero_accel = 111,
                  rate_above_tick = 112, accel_too_low = 113, bad_byte = 114, overrun = 115,
                  mode_one_axis = 116, arc_too_big = 117, soft_limit = 118, homing_failed = 119;
}  // namespace code

// The number a refusal of planner::check() answers with (its text:
// planner::refusal_text()).
uint8_t refusal_code(planner::Refusal r);

void ok();
void error(uint8_t grbl_code, const char* progmem_reason);
// A refusal whose reason is written in pieces between the two.
void error_begin();
void error_end(uint8_t grbl_code);
// Marlin's answer to a code it does not have: `echo:Unknown command:
// "<line>"` and `ok` (the print goes on).
void unknown_command(const char* line);
void info_begin();
void info_end();
// `echo:<text>` or `[MSG:<text>]` as one line.
void info_P(const char* progmem_text);

// Lines of their own, not an answer to any line: the machine has stopped
// (a hard limit, a soft reset in motion) and refuses motion until unlocked.
// grbl: `ALARM:<n>` (grbl's alarm number), `[MSG:<reason>]` and `[MSG:'$X'
// to unlock]`; Marlin: `Error:<reason>, M999 unlocks`.
void alarm(uint8_t grbl_alarm, const char* progmem_reason);

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
